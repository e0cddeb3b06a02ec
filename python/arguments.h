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
// A random seed: any integer in [0, 2^64 - 1], as the CLI's --seed takes
// ("seed: expected an integer in [0, 18446744073709551615], got -1").
uint64_t checkedSeed(py::handle integer);

// The type of every `seed` argument: converted by checkedSeed, so a seed out of range is a ValueError
// naming `seed`, not pybind's TypeError for an integer beyond int64; anything that is not an integer
// is a TypeError, as for the other integer arguments.
struct Seed {
  uint64_t value = 0;
};
// Worker threads: 1 .. 1024, or 0 (all cores) for None.
int checkedThreads(const std::optional<int64_t>& threads);
// Raises MemoryError (core's OutOfMemoryError) when `bytes` for `what` exceed the available memory;
// only measured for allocations over 64 MB.
void checkAllocation(uint64_t bytes, const std::string& what);

}  // namespace penumbra::python

namespace pybind11::detail {

template <>
struct type_caster<penumbra::python::Seed> {
  PYBIND11_TYPE_CASTER(penumbra::python::Seed, const_name("int"));

  bool load(handle src, bool /*convert*/) {
    if (!src || PyFloat_Check(src.ptr())) return false;
    object integer = reinterpret_steal<object>(PyNumber_Index(src.ptr()));
    if (!integer) {
      PyErr_Clear();
      return false;
    }
    value.value = penumbra::python::checkedSeed(integer);
    return true;
  }

  static handle cast(penumbra::python::Seed seed, return_value_policy, handle) {
    return PyLong_FromUnsignedLongLong(seed.value);
  }
};

}  // namespace pybind11::detail
