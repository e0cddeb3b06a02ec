// Checks of the numeric arguments the module's functions share: the CLI's ranges and words
// (core/math/argument_checks.h), as ValueErrors that name the argument.
#pragma once

#include <pybind11/pybind11.h>

#include <cstdint>
#include <optional>
#include <string>

namespace penumbra::python {

namespace py = pybind11;

// Seconds: a finite number > 0 ("time: expected a finite number > 0, got inf").
double checkedSeconds(double seconds, const char* argument);
// An integer in [lo, hi] ("spp: expected an integer in [1, 1073741824], got 0").
int64_t checkedCount(int64_t value, int64_t lo, int64_t hi, const char* argument);
uint64_t checkedSeed(int64_t seed);
// Worker threads: 1 .. 1024, or 0 (all cores) for None.
int checkedThreads(const std::optional<int64_t>& threads);
// Raises MemoryError (core's OutOfMemoryError) when `bytes` for `what` exceed the available memory;
// only measured for allocations over 64 MB.
void checkAllocation(uint64_t bytes, const std::string& what);

}  // namespace penumbra::python
