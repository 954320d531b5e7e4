#include "odometry_option.hpp"

#include <cstdio>

namespace trn::cli {

void add_odometry_option(CLI::App& cmd, std::string& value, const std::vector<std::string>& choices, const std::string& what) {
    value = choices.front();
    cmd.add_option("--odometry", value, what)->capture_default_str()->check(CLI::IsMember(choices));
}

void record_odometry(const std::string& odometry, const filter::VisualOdometrySource* visual, LocalizationReport& report) {
    report.strings["odometry"] = visual ? "visual (ORB + RANSAC similarity frame to frame, phase-correlation fallback)" : odometry;
    if (!visual) return;
    const auto& c = visual->counts();
    report.numbers["visual_odometry_feature_steps"] = static_cast<double>(c.features);
    report.numbers["visual_odometry_phase_steps"] = static_cast<double>(c.phase);
    report.numbers["visual_odometry_lost_steps"] = static_cast<double>(c.lost);
    report.numbers["visual_odometry_no_frame_steps"] = static_cast<double>(c.no_frame);
    char line[200];
    std::snprintf(line, sizeof line, "visual odometry: %zu steps by features, %zu by phase correlation, %zu lost, %zu without a frame\n",
                  c.features, c.phase, c.lost, c.no_frame);
    report.after_summary += line;
}

}  // namespace trn::cli
