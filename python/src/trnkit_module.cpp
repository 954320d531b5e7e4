// `trnkit._trnkit`: the compiled half of the `trnkit` package (python/trnkit/: the public names,
// keyword checks, docstrings and stubs live there). One register_* per binding source file; a new
// binding (e.g. a Localizer) is one more py_*.cpp registered here and re-exported by __init__.py.
#include <pybind11/pybind11.h>

#include <string>

#include "py_backend.hpp"
#include "py_energy.hpp"
#include "py_errors.hpp"
#include "py_localize.hpp"
#include "py_mavlink.hpp"
#include "trn/build_info.hpp"

PYBIND11_MODULE(_trnkit, m) {
    m.doc() = "trnkit's compiled primitives; import trnkit, not this module";
    m.attr("__version__") = std::string(trn::build_info().version);
    m.attr("git_commit") = std::string(trn::build_info().git_commit);
    trn::py::register_errors(m);
    trn::py::register_backend(m);
    trn::py::register_energy(m);
    trn::py::register_localize(m);
    trn::py::register_mavlink(m);
}
