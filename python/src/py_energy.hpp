#pragma once
// Live power sources, measurement windows and integrate_energy (python/trnkit/_energy.py wraps them).
#include <pybind11/pybind11.h>

namespace trn::py {

void register_energy(pybind11::module_& m);

}  // namespace trn::py
