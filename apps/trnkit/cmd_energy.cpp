// Placeholder until the subsystem lands: the subcommand exists and says so plainly.
#include "commands.hpp"
#include "trn/error.hpp"

namespace trn::cli {

void add_energy_command(CLI::App& app) {
    auto* cmd = app.add_subcommand("energy", "Power logs -> joules per frame -> platform comparison (not built yet)");
    cmd->allow_extras();
    cmd->callback([] { throw Error("'energy' is not part of this build yet"); });
}

}  // namespace trn::cli
