#pragma once
// Each subcommand of the trnkit CLI lives in its own cmd_*.cpp and registers itself here.
#include <CLI/CLI.hpp>

namespace trn::cli {

void add_devices_command(CLI::App& app);
void add_sobel_command(CLI::App& app);
void add_score_command(CLI::App& app);
void add_demo_command(CLI::App& app);
void add_frames_command(CLI::App& app);    // cmd_frames.cpp   (energy frame runner)
void add_energy_command(CLI::App& app);    // cmd_energy.cpp   (energy harness)
void add_simulate_command(CLI::App& app);  // cmd_simulate.cpp (flight simulator)
void add_check_command(CLI::App& app);     // cmd_check.cpp    (cross-backend scoring table)
void add_localize_command(CLI::App& app);  // cmd_localize.cpp (DPC-PFL on an AIR folder)
void add_experiment_command(CLI::App& app);  // cmd_experiment.cpp (dissertation studies)
void add_register_command(CLI::App& app);  // cmd_register.cpp (poses of real frames on a map)
void add_import_photos_command(CLI::App& app);  // cmd_import_photos.cpp (camera photos -> AIR folder)

}  // namespace trn::cli
