#pragma once
// `trnkit experiment NAME`: reproduces one of the dissertation's studies (metrics, heading,
// sampling, conversion, robustness, odometry; odometry-wind on the -wind presets) under a filter
// profile (ours or dissertation). Every study is split into independent jobs; each
// job writes one JSON into the output folder (finished jobs are skipped, so runs resume) and
// appends one line to the results store, results/<study>/<profile>.jsonl (kept in the repository;
// --resume skips what it holds and merges from it), and
// `merge` turns the job outputs into Markdown + CSV tables with the dissertation's numbers in
// adjacent columns, gnuplot plots and a provenance JSON. A merge refuses job outputs whose
// configuration differs from the one asked for.
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "trn/backend_options.hpp"
#include "trn/export.hpp"

TRN_API_BEGIN
namespace trn::experiments {

struct ExperimentOptions {
    std::string study;           // one of study_names()
    std::string out;             // output folder (default: experiments/<study>[-quick])
    std::string backend = "cpu";  // scoring backend spec (registry.hpp)
    BackendOptions backend_options;  // how that backend is created
    std::string shared_data;     // folder holding orthophoto.png for the real-map jobs; "" : procedural maps only
    std::string shard = "1/1";   // run jobs i, i+n, i+2n ... (1-based i)
    std::vector<std::string> jobs;  // run only the jobs with these ids (what --list-jobs prints); empty: every job
    std::uint64_t seed = 1;
    std::string profile = "ours";  // the filter's settings: ours or dissertation (filter::Profile)
    std::string lock_monitor;      // "on", "off"; "": the profile's (ours on, dissertation off)
    // The results store: one JSON line per finished job (results_store.hpp), default
    // results/<study>/<profile>[-quick].jsonl; "none": not written.
    std::string results;
    bool resume = false;         // skip the jobs the store holds for this configuration; merge from it too
    double init_radius_m = NAN;  // flight studies: particles start within this radius (m); NaN: the study's 300 m
    // Flight studies, for the sensitivity to what the text leaves open (issue 47 item 5): the KLD
    // particle maximum and the KLD upper quantile (0.9: z = +1.28, 0.1: z = -1.28); 0 / NaN: the profile's.
    std::size_t max_particles = 0;
    double kld_upper_quantile = NAN;
    bool quick = false;          // reduced but meaningful version (CI)
    bool list_jobs = false;      // print one command per job and exit
    bool list_ids_only = false;  // with list_jobs: print only the job ids, one a line (scripts/experiment-*)
    // With list_ids_only: each id is followed by a space and its inputs key (Study::inputs_key, the
    // id itself when the job shares nothing): jobs of one key run in one process build their maps once.
    bool list_keys = false;
    bool merge_only = false;     // only build tables from finished job outputs
    bool prepare_only = false;   // only create/mark the output folder and check finished jobs (before a dispatch)
    bool no_merge = false;       // run jobs only (cluster shards); merge later
    bool partial = false;        // merge whatever jobs are finished (tables say so); for documented subsets
    bool no_plots = false;
    bool force = false;          // write into a non-empty folder that is not this study's output
    bool progress = true;        // progress bar on stderr
};

std::vector<std::string> study_names();

// --shard i/n: run jobs i-1, i-1+n, ... Parsed strictly (decimal digits, no wrap, no overflow);
// throws trn::Error naming the option otherwise.
inline constexpr std::size_t kMaxShards = 1'000'000;
struct Shard {
    std::size_t index = 0, count = 1;  // 0-based slice index, number of slices
};
Shard parse_shard(const std::string& text);

// Runs (part of) a study as the options say; returns the number of jobs still missing (0 when the
// tables were built). Throws trn::Error naming the bad option or the inconsistent job output.
std::size_t run_experiment(const ExperimentOptions& options);

}  // namespace trn::experiments
TRN_API_END
