// `trnkit experiment NAME`: reproduces one of the dissertation's studies as independent, resumable
// jobs and builds its tables (see trn/experiments/experiment.hpp and docs/RESULTS.md).
#include <cstdlib>
#include <iostream>

#include "backend_env.hpp"
#include "commands.hpp"
#include "options.hpp"
#include "trn/error.hpp"
#include "trn/experiments/experiment.hpp"

namespace trn::cli {

void add_experiment_command(CLI::App& app) {
    auto a = std::make_shared<experiments::ExperimentOptions>();
    auto* cmd = app.add_subcommand("experiment", "Reproduce a dissertation study: metrics, heading, sampling, conversion, robustness, odometry (odometry-wind: the -wind presets; odometry-visual: odometry from the frames, Table 3.13)");
    cmd->add_option("name", a->study, "Study to run")->required()->check(CLI::IsMember(experiments::study_names()));
    cmd->add_flag("--quick", a->quick, "Reduced but meaningful version (CI)");
    cmd->add_option("--out", a->out, "Output folder (default: experiments/NAME[-quick])");
    cmd->add_option("--backend", a->backend, "Scoring backend (cpu, cpu-ref, opencl:0, vulkan:0 ...)")->capture_default_str();
    cmd->add_option("--seed", a->seed, "Seed of maps, flights and filters")->capture_default_str()->transform(any_seed());
    cmd->add_option("--shard", a->shard, "Run the i-th of n slices of the job list (i/n)")
        ->capture_default_str()
        ->check(CLI::Validator(
            [](std::string& text) -> std::string {
                try {
                    experiments::parse_shard(text);
                } catch (const Error& e) {
                    return e.what();
                }
                return {};
            },
            "i/n"));
    cmd->add_option("--job", a->job, "Run only this job (ids from --list-jobs)");
    cmd->add_flag("--list-jobs", a->list_jobs, "Print one command per job (for GNU parallel / Slurm), then the merge command");
    cmd->add_flag("--merge", a->merge_only, "Only build the tables from finished job outputs");
    cmd->add_flag("--no-merge", a->no_merge, "Run jobs only; merge later");
    cmd->add_flag("--partial", a->partial, "Merge the finished jobs even when some are missing (a documented subset)");
    cmd->add_flag("--no-plots", a->no_plots, "Skip gnuplot");
    cmd->add_flag("--force", a->force, "Write into a non-empty folder that is not an earlier output of this study");
    cmd->callback([a] {
        a->progress = true;
        a->backend_options = backend_options_from_environment();
        if (const char* dir = std::getenv("TRN_SHARED_DATA")) a->shared_data = dir;  // the real-map jobs
        const std::size_t missing = experiments::run_experiment(*a);
        if (missing && !a->list_jobs && !a->no_merge && !a->partial) throw trn::Error("experiment " + a->study + ": " + std::to_string(missing) + " job(s) not finished");
    });
}

}  // namespace trn::cli
