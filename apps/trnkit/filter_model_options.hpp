#pragma once
// The particle filter's motion-model and lock-monitor options, shared by `localize` and `demo`:
// registered on a subcommand with their ranges (checked by CLI11 at parse time through real_in, so a
// bad value fails before any work with one line naming the option) and copied into a FilterConfig.
#include <CLI/CLI.hpp>

#include "trn/filter/particle_filter.hpp"

namespace trn::cli {

struct FilterModelArgs {
    filter::MotionModel motion;
    filter::LockMonitorConfig lock;
    bool along_heading = false, no_lock_monitor = false;
};

void add_filter_model_options(CLI::App& cmd, FilterModelArgs& args);
// Copies the (already range-checked) options into `config`.
void apply_filter_model_options(const FilterModelArgs& args, filter::FilterConfig& config);

}  // namespace trn::cli
