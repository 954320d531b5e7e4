// Fuzz entry: the AIR metadata.csv reader (host/sim/air_format.cpp, AirMetadataParser). A refusal
// must be trn::Error; every record it accepts has a file name, finite numbers (or a whole group of
// columns empty) and a later line.
#include <cmath>
#include <sstream>
#include <vector>

#include "fuzz_check.hpp"
#include "trn/error.hpp"
#include "trn/sim/air_format.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    using trn::fuzz::require;
    std::istringstream in{std::string(trn::fuzz::as_text(data, size))};
    try {
        trn::sim::AirMetadataParser parser(in, "fuzz/metadata.csv");
        trn::sim::AirRecord r;
        int last_line = parser.line();
        while (parser.next(r)) {
            require(parser.line() > last_line, "line number did not advance");
            last_line = parser.line();
            require(!r.filename.empty(), "empty Filename accepted");
            require(r.relative_altitude_m > 0 && r.relative_altitude_m <= 20000, "RelativeAltitude outside (0, 20000] m accepted");
            // Every number finite, except groups of columns left empty as a whole (NaN: not measured).
            const std::vector<std::vector<double>> groups = {
                {r.latitude_deg, r.longitude_deg},  {r.imu.x, r.imu.y, r.imu.z, r.imu.w},
                {r.pose_m.x, r.pose_m.y, r.pose_m.z}, {r.orientation.x, r.orientation.y, r.orientation.z, r.orientation.w},
                {r.map_x, r.map_y},                 {r.svo_m.x, r.svo_m.y, r.svo_m.z}};
            require(std::isfinite(r.relative_altitude_m), "non-finite RelativeAltitude accepted");
            for (const auto& g : groups) {
                const bool empty = std::isnan(g[0]);
                for (double v : g) require(empty ? std::isnan(v) : std::isfinite(v), "non-finite number, or a group partly empty, accepted");
            }
        }
    } catch (const trn::Error&) {
    }
    return 0;
}
