#pragma once
// --heading compass|none and the compass-less yaw prior (--start-yaw-deg, --start-yaw-sd-deg) of
// `localize` and `demo`: registered with their ranges, cross-checked (errors name the option) and
// copied into a LocalizerConfig.
#include <cmath>
#include <string>

#include <CLI/CLI.hpp>

#include "trn/localize/localizer.hpp"
#include "trn/localize/localizer_defaults.hpp"

namespace trn::cli {

struct HeadingArgs {
    std::string heading = "compass";
    double start_yaw_deg = NAN, start_yaw_sd_deg = NAN;  // NaN: uniform / localize::kCompasslessYawSdDeg
};


void add_heading_options(CLI::App& cmd, HeadingArgs& args);
// Throws trn::Error naming the option: the yaw prior without --heading none, or a compass-mode
// prior option (`compass_options`: e.g. "--start-heading-deg" when given) with it.
void apply_heading_options(const HeadingArgs& args, localize::LocalizerConfig& config, const std::string& compass_option_given = "");
// "uniform" or "Y +- S deg" (for the printout and summary.json).
std::string describe_yaw_prior(const HeadingArgs& args);

}  // namespace trn::cli
