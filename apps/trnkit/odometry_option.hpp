#pragma once
// `--odometry` of `demo` (simulated | visual) and `localize` (folder | visual): which odometry the
// filter is fed, checked by CLI11 at parse time.
#include <string>
#include <vector>

#include <CLI/CLI.hpp>


namespace trn::cli {

// `choices` first = the default (shown in --help).
void add_odometry_option(CLI::App& cmd, std::string& value, const std::vector<std::string>& choices, const std::string& what);

}  // namespace trn::cli
