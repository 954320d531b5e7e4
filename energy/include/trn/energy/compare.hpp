#pragma once
// Platform comparison from run reports (`trnkit energy compare`): per platform n, mean, SD,
// median, IQR and 95 % CI of energy per frame and of frame time; Shapiro-Wilk; pairwise Welch
// and/or Student t-tests, the Mann-Whitney U rank test and the energy ratio with a delta-method
// and a bootstrap CI, each family Holm-corrected. Flagged frames are left out and counted.
//
// The unit of the tests: with several runs per platform the run is the unit (per-run mean
// energies; frames of one run are not independent samples of the platform), else the frame.
#include <optional>
#include <string>
#include <vector>

#include "trn/energy/run_report.hpp"
#include "trn/energy/stats.hpp"
#include "trn/export.hpp"

TRN_API_BEGIN
namespace trn::energy {

enum class TestUnit {
    Auto,    // runs when every platform has >= 2 runs, else frames
    Frames,  // every usable frame is a value (frames of several runs pooled)
    Runs,    // each run's mean energy per frame is a value
};

struct CompareOptions {
    bool student = false;  // Student's t (equal variances) instead of Welch
    bool both = false;     // Welch and Student, each with its own Holm correction
    bool net = true;       // net (above idle) energy; false: gross
    double alpha = 0.05;
    TestUnit unit = TestUnit::Auto;
    std::size_t bootstrap_resamples = 10000;
};

struct PlatformStats {
    std::string name;
    std::vector<double> energy_mj, frame_ms;  // usable frames only
    std::vector<double> run_mean_mj;          // per run with usable frames: its mean energy per frame
    std::size_t runs = 0, flagged = 0;
    Summary energy, time, run_means;
    double within_run_sd = 0;  // pooled SD of frames about their run's mean (0 with one frame per run)
    std::optional<ShapiroWilk> shapiro;  // of the test unit's values; empty when it cannot be computed (see shapiro_note)
    std::size_t shapiro_used = 0;        // values tested (a subsample of 5000 above 5000)
    std::string shapiro_note;
    bool normality_rejected(double alpha) const { return shapiro && shapiro->p < alpha; }
};

struct TTestResult {
    std::string test;  // "welch" or "student"
    TTest t;
    double p_holm = 1;
};

struct PairStats {
    std::string a, b;
    std::size_t n_a = 0, n_b = 0;        // values in the test unit
    std::vector<TTestResult> t_tests;    // the chosen test, or Welch then Student
    RankTest rank;
    double rank_p_holm = 1;
    Ratio ratio;                         // energy a / energy b, delta-method CI
    std::optional<BootstrapRatio> bootstrap;
    bool normality_rejected = false;     // Shapiro-Wilk rejected for a or b: read the rank test and bootstrap CI
    std::string note;                    // why the tests could not be run, when they could not
    const TTest& t() const { return t_tests.front().t; }
    double p_holm() const { return t_tests.front().p_holm; }
};

struct RunInput {
    std::string path, sha256;
    RunReport report;
};

struct Comparison {
    CompareOptions options;
    std::string unit;  // "runs" or "frames", as decided
    std::vector<RunInput> inputs;
    std::vector<PlatformStats> platforms;
    std::vector<PairStats> pairs;
    std::vector<std::string> notes;  // what a reader must know (unit, subsampling, non-normal data)
};

Comparison compare_runs(std::vector<RunInput> inputs, const CompareOptions& options);
// Reads, hashes and compares report files.
Comparison compare_files(const std::vector<std::string>& paths, const CompareOptions& options);

// The tables: energy per frame per platform, normality, pairwise t-tests, rank tests and ratios.
std::string tables_markdown(const Comparison& c);
std::string energy_table_csv(const Comparison& c);
std::string shapiro_table_csv(const Comparison& c);
std::string ttest_table_csv(const Comparison& c);
std::string rank_ratio_table_csv(const Comparison& c);
// A few lines for a terminal: per platform mean and CI, per pair the verdicts.
std::string comparison_summary_text(const Comparison& c);
// Every figure above plus provenance: input hashes, each run's config, alignment and calibration.
std::string comparison_json(const Comparison& c);

}  // namespace trn::energy
TRN_API_END
