// filmgrain._filmgrain: the extension behind `import filmgrain` (python/filmgrain). Errors
// of the library become Python exceptions with the CLI's messages: ValueError for invalid
// arguments, parameters and malformed payloads, OSError for files, MemoryError.
#include <pybind11/pybind11.h>

#include <new>

#include "command_line.hpp"
#include "filmgrain/error.hpp"
#include "python/python_module.hpp"

namespace py = pybind11;

PYBIND11_MODULE(_filmgrain, m) {
    m.doc() = "filmgrain's C++ core: sessions, parameter forms, render / apply / analyze jobs";
    m.attr("__version__") = FILMGRAIN_VERSION;
    py::register_exception_translator([](std::exception_ptr p) {
        try {
            if (p) std::rethrow_exception(p);
        } catch (const filmgrain::Error& e) {
            switch (e.code()) {
            case filmgrain::ErrorCode::kIo: PyErr_SetString(PyExc_OSError, e.what()); return;
            case filmgrain::ErrorCode::kOutOfMemory: PyErr_SetString(PyExc_MemoryError, e.what()); return;
            case filmgrain::ErrorCode::kInternal: PyErr_SetString(PyExc_RuntimeError, e.what()); return;
            default: PyErr_SetString(PyExc_ValueError, e.what()); return;
            }
        } catch (const filmgrain::cli::CommandExit& e) {
            PyErr_SetString(PyExc_RuntimeError, ("the command ended with status " + std::to_string(e.status)).c_str());
        }
    });
    filmgrain::python::register_session(m);
    filmgrain::python::register_video_files(m);
    filmgrain::python::register_commands(m);
}
