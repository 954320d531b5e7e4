// MAVLink v2 out from Python: the C++ Stream itself; names, keyword checks and docstrings are
// python/trnkit/_mavlink.py's.
#include "py_mavlink.hpp"

#include <pybind11/stl.h>

#include "trn/io/mavlink_stream.hpp"

namespace trn::py {

namespace pyb = pybind11;
namespace mav = io::mavlink;

void register_mavlink(pyb::module_& m) {
    pyb::class_<mav::Stream>(m, "_MavlinkStream")
        .def(pyb::init([](unsigned system_id, unsigned component_id, unsigned messages, unsigned sensor_id, unsigned satellites) {
                 mav::StreamConfig c;  // ranges checked by _mavlink.py
                 c.identity = {static_cast<std::uint8_t>(system_id), static_cast<std::uint8_t>(component_id)};
                 c.messages = messages, c.sensor_id = static_cast<std::uint8_t>(sensor_id), c.satellites = static_cast<std::uint8_t>(satellites);
                 return mav::Stream(c);
             }),
             pyb::arg("system_id"), pyb::arg("component_id"), pyb::arg("messages"), pyb::arg("sensor_id"), pyb::arg("satellites"))
        .def(
            "encode",
            [](mav::Stream& s, std::uint64_t time_us, bool valid, bool reset, double lat_deg, double lon_deg, double alt_msl_m, double north_m,
               double east_m, double cov_nn, double cov_ne, double cov_ee, double spread_m, double vel_north, double vel_east, double vel_var,
               double yaw_rad, double yaw_var, std::uint32_t processing_us) {
                mav::NavFix f;
                f.time_us = time_us, f.valid = valid, f.reset = reset, f.lat_deg = lat_deg, f.lon_deg = lon_deg, f.alt_msl_m = alt_msl_m;
                f.north_m = north_m, f.east_m = east_m, f.cov_nn = cov_nn, f.cov_ne = cov_ne, f.cov_ee = cov_ee, f.spread_m = spread_m;
                f.vel_north = vel_north, f.vel_east = vel_east, f.vel_var = vel_var, f.yaw_rad = yaw_rad, f.yaw_var = yaw_var;
                f.processing_us = processing_us;
                const std::vector<std::uint8_t> bytes = s.step(f);
                return pyb::bytes(reinterpret_cast<const char*>(bytes.data()), bytes.size());
            },
            pyb::arg("time_us"), pyb::arg("valid"), pyb::arg("reset"), pyb::arg("lat_deg"), pyb::arg("lon_deg"), pyb::arg("alt_msl_m"),
            pyb::arg("north_m"), pyb::arg("east_m"), pyb::arg("cov_nn"), pyb::arg("cov_ne"), pyb::arg("cov_ee"), pyb::arg("spread_m"),
            pyb::arg("vel_north"), pyb::arg("vel_east"), pyb::arg("vel_var"), pyb::arg("yaw_rad"), pyb::arg("yaw_var"),
            pyb::arg("processing_us"));
}

}  // namespace trn::py
