// Integer arguments of the Python API (seed, count, first, steps, run, jobs):
// checked for their range here, so that -1 or 2**64 gives rrlab.ScenarioError
// (a ValueError) naming the argument instead of pybind11's TypeError.
#pragma once

#include <pybind11/pybind11.h>

#include <cstdint>
#include <limits>
#include <string>

namespace rrlab::python {

constexpr std::int64_t kMaxWholeNumber = std::numeric_limits<std::int64_t>::max();

// `value` as a whole number in [min, max]: a Python int or anything with
// __index__ (numpy's integers), never a bool, a float or a string; else a
// ScenarioError at `name`: "must be a whole number in [MIN, MAX], got VALUE".
std::int64_t whole_number(const pybind11::handle& value, const std::string& name, std::int64_t min, std::int64_t max);

}  // namespace rrlab::python
