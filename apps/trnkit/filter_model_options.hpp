#pragma once
// The particle filter's motion-model and lock-monitor options, shared by `localize` and `demo`:
// registered on a subcommand, then checked (finite, in range, the message names the option) and
// copied into a FilterConfig.
#include <CLI/CLI.hpp>

#include "trn/filter/particle_filter.hpp"

namespace trn::cli {

struct FilterModelArgs {
    filter::MotionModel motion;
    filter::LockMonitorConfig lock;
    bool along_heading = false, no_lock_monitor = false;
};

void add_filter_model_options(CLI::App& cmd, FilterModelArgs& args);
// Throws trn::Error "--option VALUE: ..." for a value out of range (call before any work).
void check_filter_model_options(const FilterModelArgs& args);
// Checks, then copies the options into `config`.
void apply_filter_model_options(const FilterModelArgs& args, filter::FilterConfig& config);

}  // namespace trn::cli
