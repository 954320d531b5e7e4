#pragma once
// trnkit.integrate_energy: `trnkit energy integrate` as a function returning per-frame arrays.
#include <pybind11/pybind11.h>

namespace trn::py {

void register_energy(pybind11::module_& m);

}  // namespace trn::py
