// trnkit: command-line entry point. Subcommands are registered from cmd_*.cpp; every failure
// prints one line naming what was wrong and exits non-zero.
#include <iostream>

#include "commands.hpp"
#include "trn/error.hpp"

int main(int argc, char** argv) {
    CLI::App app{"trnkit: terrain-relative navigation kit (particle-filter map matching, Sobel, energy)"};
    app.require_subcommand(1);
    trn::cli::add_devices_command(app);
    trn::cli::add_sobel_command(app);
    trn::cli::add_score_command(app);
    trn::cli::add_demo_command(app);
    trn::cli::add_frames_command(app);
    trn::cli::add_energy_command(app);
    trn::cli::add_simulate_command(app);
    trn::cli::add_check_command(app);
    trn::cli::add_localize_command(app);
    trn::cli::add_experiment_command(app);
    try {
        app.parse(argc, argv);
    } catch (const CLI::ParseError& e) {
        return app.exit(e);
    } catch (const trn::Error& e) {
        std::cerr << "trnkit: error: " << e.what() << "\n";
        return 1;
    } catch (const std::exception& e) {
        std::cerr << "trnkit: unexpected error: " << e.what() << "\n";
        return 2;
    }
    return 0;
}
