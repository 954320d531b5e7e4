#include "odometry_option.hpp"

namespace trn::cli {

void add_odometry_option(CLI::App& cmd, std::string& value, const std::vector<std::string>& choices, const std::string& what) {
    value = choices.front();
    cmd.add_option("--odometry", value, what)->capture_default_str()->check(CLI::IsMember(choices));
}

}  // namespace trn::cli
