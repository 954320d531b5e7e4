#include "mavlink_option.hpp"

#include <sstream>

#include "options.hpp"
#include "trn/error.hpp"

namespace trn::cli {
namespace {

unsigned parse_messages(const std::string& text) {
    unsigned set = 0;
    std::stringstream list(text);
    for (std::string name; std::getline(list, name, ',');) {
        if (name == "gps_input") set |= io::mavlink::kSendGpsInput;
        else if (name == "global_position" || name == "global_position_sensor") set |= io::mavlink::kSendGlobalPosition;
        else if (name == "odometry") set |= io::mavlink::kSendOdometry;
        else
            throw Error("--mavlink-messages: '" + name.substr(0, 40) +
                        "' is not one of gps_input, global_position (GLOBAL_POSITION_SENSOR), odometry");
    }
    if (set == 0) throw Error("--mavlink-messages: empty; name at least one of gps_input, global_position, odometry");
    return set;
}

io::mavlink::StreamConfig stream_config(const MavlinkArgs& a) {
    io::mavlink::StreamConfig c;
    c.messages = parse_messages(a.messages);
    c.identity.system_id = static_cast<std::uint8_t>(a.system_id), c.identity.component_id = static_cast<std::uint8_t>(a.component_id);
    c.sensor_id = static_cast<std::uint8_t>(a.sensor_id);
    return c;
}

}  // namespace

void add_mavlink_options(CLI::App& cmd, MavlinkArgs& a) {
    CLI::Option* target = cmd.add_option("--mavlink", a.target,
                   "Stream each step's estimate as MAVLink v2 to udp:HOST:PORT (or udpout:HOST:PORT): HEARTBEAT at 1 Hz, GPS_INPUT, "
                   "GLOBAL_POSITION_SENSOR, ODOMETRY; 'no fix' while the filter is lost (docs/AUTOPILOT.md). Needs latitude/longitude: "
                   "a GeoTIFF map or flight.json's origin");
    cmd.add_option("--mavlink-messages", a.messages, "Which messages --mavlink sends, comma-separated: gps_input, global_position, odometry")
        ->capture_default_str()
        ->needs(target);
    cmd.add_option("--mavlink-sysid", a.system_id, "MAVLink system id of the messages (the vehicle's, usually 1)")
        ->capture_default_str()
        ->transform(whole_in(1, 255))
        ->needs(target);
    cmd.add_option("--mavlink-compid", a.component_id, "MAVLink component id of the messages (197: MAV_COMP_ID_VISUAL_INERTIAL_ODOMETRY)")
        ->capture_default_str()
        ->transform(whole_in(1, 255))
        ->needs(target);
    cmd.add_option("--mavlink-sensor-id", a.sensor_id,
                   "GPS_INPUT's gps_id (0: ArduPilot's first GPS) and GLOBAL_POSITION_SENSOR's id (PX4: EKF2_AGP0_ID where it has one)")
        ->capture_default_str()
        ->transform(whole_in(0, 255))
        ->needs(target);  // an id without --mavlink would be silently unused
}

MavlinkOut::MavlinkOut(const MavlinkArgs& a, double metres_per_pixel, bool compassless)
    : stream_(stream_config(a)), sender_(io::mavlink::parse_endpoint(a.target, "--mavlink")), target_(a.target),
      fixes_(metres_per_pixel, compassless) {}

void MavlinkOut::step(const localize::LocalizationRow& row, const localize::Estimate& e) {
    const io::mavlink::NavFix f = fixes_.fix(row, e);
    sender_.send(stream_.step(f));
    ++steps_;
    if (!f.valid) ++lost_;
}

std::string MavlinkOut::summary() const {
    return "mavlink: " + std::to_string(steps_) + " steps (" + std::to_string(lost_) + " without a fix) sent to " + target_ + " in " +
           std::to_string(sender_.sent()) + " datagrams" +
           (sender_.refused() ? " (" + std::to_string(sender_.refused()) + " refused: nobody listening)" : std::string()) + "\n";
}

}  // namespace trn::cli
