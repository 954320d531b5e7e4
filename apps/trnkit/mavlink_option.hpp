#pragma once
// `localize --mavlink udp:HOST:PORT`: each filter step's estimate streamed as MAVLink v2
// (trn/io/mavlink_stream.hpp; docs/AUTOPILOT.md), with the options that pick messages and ids.
#include <cstdint>
#include <memory>
#include <string>

#include <CLI/CLI.hpp>

#include "trn/io/mavlink_stream.hpp"
#include "trn/io/mavlink_udp.hpp"
#include "trn/localize/localization.hpp"
#include "trn/localize/mavlink_fix.hpp"

namespace trn::cli {

struct MavlinkArgs {
    std::string target;  // empty: no MAVLink
    std::string messages = "gps_input,global_position,odometry";
    unsigned system_id = 1, component_id = 197, sensor_id = 0;
};

void add_mavlink_options(CLI::App& cmd, MavlinkArgs& args);

// The stream to one peer; checks every option before the run.
class MavlinkOut {
public:
    // compassless: the yaw is the filter's own estimate, so it is sent (a compass run would echo the compass back).
    MavlinkOut(const MavlinkArgs& args, double metres_per_pixel, bool compassless);
    void step(const localize::LocalizationRow& row, const localize::Estimate& e);
    std::string summary() const;  // one line for the console

private:
    io::mavlink::Stream stream_;
    io::mavlink::UdpSender sender_;
    std::string target_;
    localize::NavFixMaker fixes_;  // the estimate as a NavFix (trn/localize/mavlink_fix.hpp)
    std::size_t steps_ = 0, lost_ = 0;
};

}  // namespace trn::cli
