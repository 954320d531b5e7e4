#pragma once
// trnkit.Localizer, trnkit.read_air_folder, trnkit.localize and trnkit.load_gray.
#include <pybind11/pybind11.h>

namespace trn::py {

void register_localize(pybind11::module_& m);

}  // namespace trn::py
