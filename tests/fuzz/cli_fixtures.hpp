#pragma once
// The CLI fuzzer's sandbox: one temporary folder holding the fixtures (valid and broken inputs,
// stand-ins for /dev/full and /dev/null), HOME/TMPDIR/cache folders and the per-run working folder.
#include <string>
#include <vector>

#include "sandboxed_run.hpp"

namespace trn::fuzz {

struct Sandbox {
    std::string root, fx, run_dir, watch_log;
    std::string t0, t1;  // a span inside fx/power.csv (UNIX seconds)
};

// Creates the folders and fixtures. `trnkit` makes the fixtures that only it can make (an AIR
// flight, a run report); what it cannot make is reported on stdout and left out.
Sandbox make_sandbox(const std::string& trnkit, const std::string& corpus_dir, const std::vector<std::string>& env, const RunLimits& limits);

// A cheap fingerprint of fx/ (names, types, sizes, times), to notice a run that changed a fixture.
std::string fixture_fingerprint(const Sandbox& s);
// Puts fx/ back as make_sandbox left it.
void restore_fixtures(const Sandbox& s);

}  // namespace trn::fuzz
