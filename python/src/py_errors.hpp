#pragma once
// trnkit.Error (a ValueError and a RuntimeError: the library refuses bad input and reports device
// failures with the one trn::Error) and trnkit.BackendUnavailable, with the C++ translator.
#include <pybind11/pybind11.h>

namespace trn::py {

void register_errors(pybind11::module_& m);

}  // namespace trn::py
