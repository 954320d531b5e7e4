#pragma once
// The photo-import options shared by `import-photos` and `localize --photos` (--altitude-agl,
// --sensor-width-mm, --ignore-orientation, --map-origin), and the one import run both make: the
// import with its progress bar, its notes and its one-line summary.
#include <string>

#include <CLI/CLI.hpp>

#include "trn/sim/photo_import.hpp"

namespace trn::cli {

struct PhotoImportArgs {
    sim::PhotoImportOptions o;
    std::string map_origin;  // "LAT,LON", checked at parse time
};

void add_photo_import_options(CLI::App& cmd, PhotoImportArgs& args);

// Runs the import of `args` (map_origin applied), printing its progress, notes and summary.
sim::PhotoImportResult run_photo_import(PhotoImportArgs& args);

}  // namespace trn::cli
