// Fuzz entry: the particle-pose CSV reader (host/io/pose_csv.cpp). Refusing with trn::Error is fine;
// what it accepts must be finite with scale > 0 and read back identically when written as CSV.
#include <cmath>
#include <cstdio>
#include <sstream>

#include "fuzz_check.hpp"
#include "trn/error.hpp"
#include "trn/io/pose_csv.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    using trn::fuzz::require;
    std::istringstream in{std::string(trn::fuzz::as_text(data, size))};
    std::vector<trn::Pose> poses;
    try {
        poses = trn::read_poses_csv(in, "fuzz.csv");
    } catch (const trn::Error&) {
        return 0;
    }
    std::string csv = "x,y,yaw,scale\n";
    char buf[128];
    for (const auto& p : poses) {
        require(std::isfinite(p.x) && std::isfinite(p.y) && std::isfinite(p.yaw) && std::isfinite(p.scale), "non-finite pose accepted");
        require(p.scale > 0, "scale <= 0 accepted");
        require(std::fabs(p.yaw) <= 1000 && std::fabs(p.x) <= 1e7 && std::fabs(p.y) <= 1e7 && p.scale <= 1e4,
                "a pose beyond any map (|yaw| > 1000 rad, |x| > 1e7 ...) accepted");
        std::snprintf(buf, sizeof buf, "%.9g,%.9g,%.9g,%.9g\n", p.x, p.y, p.yaw, p.scale);  // 9 digits: floats exactly
        csv += buf;
    }
    std::istringstream again(csv);
    const auto back = trn::read_poses_csv(again, "round-trip.csv");  // throws (and fails) if our own output is refused
    require(back.size() == poses.size(), "round trip changed the pose count");
    for (std::size_t i = 0; i < back.size(); ++i)
        require(back[i].x == poses[i].x && back[i].y == poses[i].y && back[i].yaw == poses[i].yaw && back[i].scale == poses[i].scale,
                "round trip changed a pose");
    return 0;
}
