// Placeholder until the subsystem lands: the subcommand exists and says so plainly.
#include "commands.hpp"
#include "trn/error.hpp"

namespace trn::cli {

void add_frames_command(CLI::App& app) {
    auto* cmd = app.add_subcommand("frames", "Run a kernel K times with idle gaps and write frame markers (energy studies) (not built yet)");
    cmd->allow_extras();
    cmd->callback([] { throw Error("'frames' is not part of this build yet"); });
}

}  // namespace trn::cli
