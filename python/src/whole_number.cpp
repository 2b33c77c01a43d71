#include "whole_number.hpp"

#include <rrlab/scenario/scenario.hpp>

namespace py = pybind11;

namespace rrlab::python {

std::int64_t whole_number(const py::handle& value, const std::string& name, std::int64_t min, std::int64_t max) {
  auto refuse = [&] {
    std::string shown = py::repr(value);
    if (shown.size() > 40) shown = shown.substr(0, 37) + "...";
    return ScenarioError(name, "must be a whole number in [" + std::to_string(min) + ", " + std::to_string(max) +
                                   "], got " + shown);
  };
  if (py::isinstance<py::bool_>(value) || !PyIndex_Check(value.ptr())) throw refuse();
  const py::object index = py::reinterpret_steal<py::object>(PyNumber_Index(value.ptr()));
  int overflow = 0;
  const long long n = index ? PyLong_AsLongLongAndOverflow(index.ptr(), &overflow) : 0;
  if (!index || overflow || n < min || n > max) {
    PyErr_Clear();
    throw refuse();
  }
  return n;
}

}  // namespace rrlab::python
