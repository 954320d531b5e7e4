#pragma once
// The pieces every study is made of (private to host/experiments): a configuration, a list of
// independent jobs, a job runner and a merge step that builds tables from the job outputs.
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "trn/backend.hpp"
#include "trn/filter/particle_filter.hpp"

namespace trn::experiments {

using Json = nlohmann::ordered_json;

// The filter a study's jobs start from: the configuration's profile ("profile": ours or
// dissertation, filter::profile_config; ours when absent) with its "lock_monitor" (true / false)
// when it has one. Each study then sets what it varies (conversion, sampling, seed, radius).
// The chapter-3 studies keep the update their stores (results/) were flown with: weight 0 without a
// valid score, no tempering, scored from 0.9 of a patch on the map, lost odometry held in the world
// frame (below). Our profile's mission update (issue 42)
// came after ~40 core-hours of stored flights over maps without no-data; re-flying them under it is
// a new sweep, not a silent change of what the stored figures mean (docs/RESULTS.md, "Real flights").
inline constexpr filter::UpdateModel kStudyUpdate{
    .unknown_neutral = false, .min_valid_fraction = 0.9, .lost_body_velocity = false, .min_ess_fraction = 0};

inline filter::FilterConfig study_filter(const Json& config) {
    filter::FilterConfig f = filter::profile_config(filter::parse_profile(config.value("profile", std::string("ours"))));
    f.update = kStudyUpdate;
    if (config.contains("lock_monitor")) f.lock.enabled = config.at("lock_monitor").get<bool>();
    if (config.contains("max_particles")) f.max_particles = config.at("max_particles").get<std::size_t>();
    if (config.contains("kld_upper_quantile")) f.kld_upper_quantile = config.at("kld_upper_quantile").get<double>();
    return f;
}

// What a job may use while it runs.
struct JobContext {
    Backend& backend;
    std::uint64_t seed;
    bool quick;
    std::string job_folder;  // for per-job extra files (CSV of a run, plots)
    bool plots;
};

struct MergeContext {
    std::string out;     // output folder: tables and plots go here
    Json config;         // the study configuration every job shares
    bool plots;
};

class Study {
public:
    virtual ~Study() = default;
    virtual std::string name() const = 0;
    // Everything that makes results comparable (sizes, counts, settings); stored in every job
    // output and compared at merge time. Seed, backend and quick are added by the runner.
    virtual Json config(bool quick) const = 0;
    // One params object per job, each with a unique "id" (a file-name-safe string).
    virtual std::vector<Json> jobs(const Json& config) const = 0;
    virtual Json run_job(const Json& config, const Json& params, JobContext& context) const = 0;
    // Builds tables / plots from every job's {"params", "result"}; returns Markdown for RESULTS.md.
    virtual std::string merge(const std::vector<Json>& outputs, const MergeContext& context) const = 0;
    // A study whose jobs are another's flights (the same ids flown the same way, only fewer of
    // them) names that study: with --resume, that study's default results store counts too, so a
    // flight is flown once for both.
    virtual std::string flights_shared_with() const { return ""; }
    // Jobs with the same non-empty key build the same inputs (the procedural maps world.hpp caches
    // per process): run in one process, they build them once. A dispatcher groups by it
    // (--list-jobs=keys); "" (the default): the job shares nothing worth grouping for.
    virtual std::string inputs_key(const Json& /*params*/) const { return ""; }
};

// `orthophoto`: the real map's file (world.hpp: orthophoto_path), "" when absent.
std::unique_ptr<Study> make_metrics_study(std::string orthophoto);
std::unique_ptr<Study> make_heading_study(std::string orthophoto);
std::unique_ptr<Study> make_sampling_study();
std::unique_ptr<Study> make_conversion_study();
std::unique_ptr<Study> make_robustness_study();
// The presets or their '-wind' twins; visual: odometry from the frames (+ Table 3.13).
std::unique_ptr<Study> make_odometry_study(bool wind, bool visual = false);
// study_long_flights.cpp: the '-long' presets whole (Table 2.2 lengths); 160 px vs full-resolution templates.
std::unique_ptr<Study> make_long_odometry_study();
std::unique_ptr<Study> make_template_width_study();

}  // namespace trn::experiments
