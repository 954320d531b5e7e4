#pragma once
// `--odometry` of `demo` (simulated | visual) and `localize` (folder | visual): which odometry the
// filter is fed, checked by CLI11 at parse time; and what a visual-odometry run records in its
// summary (summary.json numbers and one console line).
#include <string>
#include <vector>

#include <CLI/CLI.hpp>

#include "localization_report.hpp"
#include "trn/filter/visual_odometry.hpp"

namespace trn::cli {

// `choices` first = the default (shown in --help).
void add_odometry_option(CLI::App& cmd, std::string& value, const std::vector<std::string>& choices, const std::string& what);
// The summary's "odometry" string, and with a visual odometry its step counts.
void record_odometry(const std::string& odometry, const filter::VisualOdometrySource* visual, LocalizationReport& report);

}  // namespace trn::cli
