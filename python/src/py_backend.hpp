#pragma once
// trnkit.Backend, trnkit.Map, trnkit.Plan and trnkit.Sampling.
#include <pybind11/pybind11.h>

namespace trn::py {

void register_backend(pybind11::module_& m);

}  // namespace trn::py
