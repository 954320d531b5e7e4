// Placeholder until the subsystem lands: the subcommand exists and says so plainly.
#include "commands.hpp"
#include "trn/error.hpp"

namespace trn::cli {

void add_simulate_command(CLI::App& app) {
    auto* cmd = app.add_subcommand("simulate", "Simulate a UAV flight over a map and write an AIR dataset (not built yet)");
    cmd->allow_extras();
    cmd->callback([] { throw Error("'simulate' is not part of this build yet"); });
}

}  // namespace trn::cli
