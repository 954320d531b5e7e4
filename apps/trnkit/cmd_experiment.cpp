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
    auto* cmd = app.add_subcommand("experiment", "Reproduce a dissertation study: metrics, heading, sampling, conversion, robustness, odometry (odometry-wind: the -wind presets; odometry-visual: odometry from the frames, Table 3.13; odometry-long: the -long presets, Table 2.2 lengths), template-width");
    cmd->add_option("name", a->study, "Study to run")->required()->check(CLI::IsMember(experiments::study_names()));
    cmd->add_flag("--quick", a->quick, "Reduced but meaningful version (CI)");
    cmd->add_option("--out", a->out, "Output folder (default: experiments/NAME[-quick])");
    cmd->add_option("--backend", a->backend, "Scoring backend (cpu, cpu-ref, opencl:0, vulkan:0 ...)")->capture_default_str();
    cmd->add_option("--seed", a->seed, "Seed of maps, flights and filters")->capture_default_str()->transform(any_seed());
    cmd->add_option("--profile", a->profile,
                    "Filter settings: ours (trnkit's reading, the default) or dissertation (the text as written where it is "
                    "unambiguous; docs/PROFILES.md); part of the configuration, default --out experiments/NAME-dissertation")
        ->capture_default_str()
        ->check(CLI::IsMember({"ours", "dissertation"}));
    cmd->add_option("--lock-monitor", a->lock_monitor,
                    "Flight and sampling studies: watch for a wrong lock, on or off (default: the profile's; ours on, dissertation off); "
                    "part of the configuration")
        ->check(CLI::IsMember({"on", "off"}));
    cmd->add_option("--max-particles", a->max_particles,
                    "Flight studies: the KLD particle maximum (default: the profile's; ours 2000, dissertation a 100000 safety cap); "
                    "part of the configuration")
        ->check(CLI::Range(100, 1000000));
    cmd->add_option("--kld-upper-quantile", a->kld_upper_quantile,
                    "Flight studies: the KLD bound's upper quantile (0.9: z = +1.28, ours; 0.1: z = -1.28, the dissertation's reading); "
                    "part of the configuration")
        ->check(real_in(0, 1, Open::both));
    cmd->add_option("--results", a->results,
                    "Results store: one JSON line per finished job, appended atomically (default: results/NAME/PROFILE[-quick].jsonl; "
                    "'none': not written)");
    cmd->add_flag("--resume", a->resume,
                  "Skip the jobs the results store holds for this configuration and merge from it (lines of another configuration "
                  "are ignored, and counted in a note); with --list-jobs=ids only the jobs still to run");
    cmd->add_option("--init-radius-m", a->init_radius_m,
                    "Flight studies: particles start within this radius (m) of the true start (default: 300, the dissertation's); "
                    "part of the configuration")
        ->check(real_in(0, 1e5, Open::low));
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
    cmd->add_option("--job", a->jobs,
                    "Run only this job (ids from --list-jobs); several: --job A,B or --job A --job B, run one after another in "
                    "one process, which builds the maps they share once (--list-jobs=keys)")
        ->delimiter(',');
    auto list_mode = std::make_shared<std::string>();
    cmd->add_flag("--list-jobs", *list_mode,
                  "Print one command per job, then the merge command; --list-jobs=ids: only the job ids, one a line (what "
                  "scripts/experiment-parallel and experiment-slurm pass to --job); --list-jobs=keys: each id, a space and its "
                  "inputs key (jobs of one key share their maps; the id itself when it shares nothing)")
        ->option_text("[=ids|keys]")
        ->check(CLI::Validator(
            [](std::string& value) -> std::string {  // a bare flag reads "true"
                return value == "true" || value == "ids" || value == "keys" ? std::string()
                                                                            : "takes no value, =ids or =keys, not '" + value + "'";
            },
            "[=ids|keys]"));
    cmd->add_flag("--merge", a->merge_only, "Only build the tables from finished job outputs");
    cmd->add_flag("--prepare", a->prepare_only,
                  "Only create the output folder and check the finished jobs against these options, before a dispatcher "
                  "starts many --job runs at once (prints how many are finished)");
    cmd->add_flag("--no-merge", a->no_merge, "Run jobs only; merge later");
    cmd->add_flag("--partial", a->partial, "Merge the finished jobs even when some are missing (a documented subset)");
    cmd->add_flag("--no-plots", a->no_plots, "Skip gnuplot");
    cmd->add_flag("--force", a->force, "Write into a non-empty folder that is not an earlier output of this study");
    cmd->callback([a, list_mode] {
        a->list_jobs = !list_mode->empty();
        a->list_ids_only = *list_mode == "ids" || *list_mode == "keys";
        a->list_keys = *list_mode == "keys";
        a->progress = true;
        a->backend_options = backend_options_from_environment();
        if (const char* dir = std::getenv("TRN_SHARED_DATA")) a->shared_data = dir;  // the real-map jobs
        const std::size_t missing = experiments::run_experiment(*a);
        // A merge that built no tables fails, --partial included (it returns 0 once it merged something).
        if (missing && !a->list_jobs && !a->prepare_only && !a->no_merge)
            throw trn::Error("experiment " + a->study + ": " + std::to_string(missing) + " job(s) not finished" +
                             (a->partial ? " (none finished: nothing to merge)" : ""));
    });
}

}  // namespace trn::cli
