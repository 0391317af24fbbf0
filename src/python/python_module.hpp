// The pieces of the `filmgrain._filmgrain` extension (one file per area).
#pragma once
#include <pybind11/pybind11.h>

namespace filmgrain::python {

namespace py = pybind11;

void register_session(py::module_& m);
void register_commands(py::module_& m);
void register_video_files(py::module_& m);

}  // namespace filmgrain::python
