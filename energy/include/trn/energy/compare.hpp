#pragma once
// Platform comparison from run reports (`trnkit energy compare`): per platform n, mean, SD,
// median, IQR and 95 % CI of energy per frame and of frame time; Shapiro-Wilk; pairwise Welch
// (or Student) t-tests with Holm correction; energy ratios with CIs. Runs with the same
// platform label are pooled. Flagged frames are left out of the statistics and counted.
#include <optional>
#include <string>
#include <vector>

#include "trn/energy/run_report.hpp"
#include "trn/energy/stats.hpp"
#include "trn/export.hpp"

TRN_API_BEGIN
namespace trn::energy {

struct CompareOptions {
    bool student = false;  // Student's t (equal variances) instead of Welch
    bool net = true;       // net (above idle) energy; false: gross
    double alpha = 0.05;
};

struct PlatformStats {
    std::string name;
    std::vector<double> energy_mj, frame_ms;  // usable frames only
    std::size_t runs = 0, flagged = 0;
    Summary energy, time;
    std::optional<ShapiroWilk> shapiro;  // empty when it cannot be computed (see shapiro_note)
    std::string shapiro_note;
};

struct PairStats {
    std::string a, b;
    TTest t;
    double p_holm = 1;
    Ratio ratio;  // energy a / energy b
    std::string note;  // why the test could not be run, when it could not
};

struct RunInput {
    std::string path, sha256;
    RunReport report;
};

struct Comparison {
    CompareOptions options;
    std::vector<RunInput> inputs;
    std::vector<PlatformStats> platforms;
    std::vector<PairStats> pairs;
};

Comparison compare_runs(std::vector<RunInput> inputs, const CompareOptions& options);
// Reads, hashes and compares report files.
Comparison compare_files(const std::vector<std::string>& paths, const CompareOptions& options);

// The dissertation's three tables: energy per frame per platform, Shapiro-Wilk, pairwise t-tests.
std::string tables_markdown(const Comparison& c);
std::string energy_table_csv(const Comparison& c);
std::string shapiro_table_csv(const Comparison& c);
std::string ttest_table_csv(const Comparison& c);
// Every figure above plus provenance: input hashes, each run's config, alignment and calibration.
std::string comparison_json(const Comparison& c);

}  // namespace trn::energy
TRN_API_END
