#pragma once
// trnkit.MavlinkEncoder's primitive: trn::io::mavlink::Stream (python/trnkit/_mavlink.py wraps it).
#include <pybind11/pybind11.h>

namespace trn::py {

void register_mavlink(pybind11::module_& m);

}  // namespace trn::py
