#include "heading_options.hpp"

#include <cstdio>

#include "options.hpp"
#include "trn/detail/angles.hpp"
#include "trn/error.hpp"

namespace trn::cli {

void add_heading_options(CLI::App& cmd, HeadingArgs& a) {
    cmd.add_option("--heading", a.heading,
                   "compass: each step's heading (magnetometer, ImuX..W) sets the particles' yaw; none: no compass, yaw is "
                   "estimated per particle and turned by the odometry's rotation (a folder's: its heading changes; visual: the "
                   "rotation between frames; simulated: the odometry's own yaw)")
        ->capture_default_str()
        ->check(CLI::IsMember({"compass", "none"}));
    cmd.add_option("--start-yaw-deg", a.start_yaw_deg,
                   "With --heading none: centre of the initial yaw prior, degrees clockwise from north (default: uniform)")
        ->check(real_in(-360, 360));
    cmd.add_option("--start-yaw-sd-deg", a.start_yaw_sd_deg,
                   "With --heading none and --start-yaw-deg: spread (sd, degrees) of the initial yaws (default 10)")
        ->check(real_in(0, 360));
}

void apply_heading_options(const HeadingArgs& a, localize::LocalizerConfig& config, const std::string& compass_option_given) {
    const bool none = a.heading == "none";
    if (!none && !std::isnan(a.start_yaw_deg))
        throw Error("--start-yaw-deg: only with --heading none (with a compass, --start-heading-deg sets the initial heading)");
    if (!none && !std::isnan(a.start_yaw_sd_deg))
        throw Error("--start-yaw-sd-deg: only with --heading none (with a compass, --heading-sd-deg sets the initial spread)");
    if (!std::isnan(a.start_yaw_sd_deg) && std::isnan(a.start_yaw_deg))
        throw Error("--start-yaw-sd-deg: needs --start-yaw-deg (without it the yaw prior is uniform)");
    if (!none) return;
    if (!compass_option_given.empty())
        throw Error(compass_option_given + ": not with --heading none (the yaw prior is --start-yaw-deg / --start-yaw-sd-deg)");
    config.filter.heading = filter::HeadingMode::None;
    config.start_heading_rad = a.start_yaw_deg * kDeg;  // NaN: uniform
    config.filter.init_heading_sd_deg = std::isnan(a.start_yaw_deg) ? NAN : std::isnan(a.start_yaw_sd_deg) ? localize::kCompasslessYawSdDeg : a.start_yaw_sd_deg;
}

std::string describe_yaw_prior(const HeadingArgs& a) {
    if (std::isnan(a.start_yaw_deg)) return "uniform";
    char buf[64];
    std::snprintf(buf, sizeof buf, "%g +- %g deg", a.start_yaw_deg, std::isnan(a.start_yaw_sd_deg) ? localize::kCompasslessYawSdDeg : a.start_yaw_sd_deg);
    return buf;
}

}  // namespace trn::cli
