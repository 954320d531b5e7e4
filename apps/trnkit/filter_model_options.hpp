#pragma once
// The particle filter's profile, motion-model, update and lock-monitor options, shared by `localize` and
// `demo`: registered on a subcommand with their ranges (checked by CLI11 at parse time through
// real_in, so a bad value fails before any work with one line naming the option) and applied on
// top of the profile's FilterConfig (filter::profile_config): an option given on the command line
// replaces the profile's value, an option not given leaves it. Under --profile ours (the default)
// that is FilterConfig{}, whose values the help shows.
#include <functional>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>

#include "trn/filter/particle_filter.hpp"

namespace trn::cli {

struct FilterModelArgs {
    std::string profile = "ours";
    std::string lock_monitor;  // "", "on", "off" ("": the profile's)
    filter::MotionModel motion;
    filter::LockMonitorConfig lock;
    filter::UpdateModel update;
    std::string update_unknown;  // "neutral", "zero" ("": the profile's)
    bool along_heading = false, no_lock_monitor = false;
    // One per option: copies the value into a config when the option was given.
    std::vector<std::pair<const CLI::Option*, std::function<void(filter::FilterConfig&)>>> given;
};

// --profile ours|dissertation (CLI11 check naming both), and --lock-monitor on|off.
CLI::Option* add_profile_option(CLI::App& cmd, std::string& profile);
CLI::Option* add_lock_monitor_option(CLI::App& cmd, std::string& lock_monitor);

void add_filter_model_options(CLI::App& cmd, FilterModelArgs& args);
// Sets `config`'s motion model and lock monitor to the profile's with the given options applied
// (the caller starts `config` from filter::profile_config of args.profile). Throws trn::Error naming the option for a combination the
// profile does not take (--motion-along-heading with --profile dissertation; --no-lock-monitor
// with --lock-monitor on).
// The checks of apply_filter_model_options alone, for before any work.
void check_filter_model_options(const FilterModelArgs& args);
void apply_filter_model_options(const FilterModelArgs& args, filter::FilterConfig& config);
}  // namespace trn::cli
