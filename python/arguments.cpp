#include "python/arguments.h"

#include <cstdio>

#include "core/math/argument_checks.h"
#include "core/render/memory_estimate.h"

namespace penumbra::python {

namespace {

std::string shortest(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.17g", v);
  return buf;
}

}  // namespace

double checkedSeconds(double seconds, const char* argument) {
  if (!isFinitePositive(seconds))
    throw py::value_error(std::string(argument) + ": " + kExpectedFinitePositive + ", got " +
                          shortest(seconds));
  return seconds;
}

int64_t checkedCount(int64_t value, int64_t lo, int64_t hi, const char* argument) {
  if (value < lo || value > hi)
    throw py::value_error(std::string(argument) + ": expected an integer in [" + std::to_string(lo) + ", " +
                          std::to_string(hi) + "], got " + std::to_string(value));
  return value;
}

uint64_t checkedSeed(py::handle integer) {
  const unsigned long long seed = PyLong_AsUnsignedLongLong(integer.ptr());
  if (seed == static_cast<unsigned long long>(-1) && PyErr_Occurred()) {
    PyErr_Clear();  // negative or beyond 64 bits
    throw py::value_error("seed: expected an integer in [0, " + std::to_string(UINT64_MAX) + "], got " +
                          std::string(py::str(integer)));
  }
  return uint64_t(seed);
}

int checkedThreads(const std::optional<int64_t>& threads) {
  return threads ? int(checkedCount(*threads, 1, kMaxThreads, "threads")) : 0;
}

void checkAllocation(uint64_t bytes, const std::string& what) {
  if (bytes > (uint64_t(64) << 20)) checkFitsInMemory(bytes, what);
}

}  // namespace penumbra::python
