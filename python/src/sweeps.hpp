// The Python package's sweeps and generated cases: rrlab.sweep runs a sweep
// spec (methods written in Python included, once registered) on worker
// threads with the GIL released, storing its runs in a SQLite file, and
// returns the report and the per-run table; rrlab.generate gives a family's
// cases as scenario documents.
#pragma once

#include <pybind11/pybind11.h>

namespace rrlab::python {

void register_sweeps(pybind11::module_& m);

}  // namespace rrlab::python
