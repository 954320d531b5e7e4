// `import trnkit`: the accelerated scorer and the energy integration for Python (docs/EMBEDDING.md).
#include <pybind11/pybind11.h>

#include <string>

#include "py_backend.hpp"
#include "py_energy.hpp"
#include "py_errors.hpp"
#include "py_localize.hpp"
#include "trn/build_info.hpp"

PYBIND11_MODULE(trnkit, m) {
    m.doc() = "trnkit: particle scoring (NCC/CC/SSD), Sobel and energy integration on CPU, OpenCL and Vulkan backends";
    m.attr("__version__") = std::string(trn::build_info().version);
    m.attr("git_commit") = std::string(trn::build_info().git_commit);
    trn::py::register_errors(m);
    trn::py::register_backend(m);
    trn::py::register_energy(m);
    trn::py::register_localize(m);
}
