// `trnkit energy bench --source SPEC -b cpu -b opencl -o DIR`: the frame runner on each backend
// while a sampler thread records power on this process's clock, then one report joining
// frames/s and joules/frame (gross, net of idle, bounds) per backend: bench.md/csv/json, the
// power log, each backend's marker file and run report (for `energy compare`), and plots.
#include <sys/utsname.h>

#include <algorithm>
#include <cstdio>
#include <iostream>
#include <set>

#include "commands.hpp"
#include "frame_workload.hpp"
#include "options.hpp"
#include "write_text.hpp"
#include "trn/energy/energy_bench.hpp"
#include "trn/energy/label_check.hpp"
#include "trn/energy/parsers.hpp"
#include "trn/energy/plots.hpp"
#include "trn/error.hpp"
#include "trn/io/gnuplot.hpp"
#include "trn/io/output_folder.hpp"
#include "trn/limits.hpp"
#include "trn/registry.hpp"

namespace trn::cli {
namespace {

std::string host_name() {
    utsname u{};
    return uname(&u) == 0 && u.nodename[0] ? std::string(u.nodename) : std::string("this-machine");
}

// The samples of `trace` around one backend's run (for its trace plot only).
energy::PowerTrace around(const energy::PowerTrace& trace, const energy::MarkerFile& m) {
    energy::PowerTrace part = trace;
    part.t.clear(), part.w.clear();
    if (m.rows.empty()) return part;
    const double a = m.rows.front().mono_start_ns * 1e-9 - 0.05, b = m.rows.back().mono_end_ns * 1e-9 + 0.05;
    for (std::size_t i = 0; i < trace.size(); ++i)
        if (trace.t[i] >= a && trace.t[i] <= b) part.t.push_back(trace.t[i]), part.w.push_back(trace.w[i]);
    return part;
}

}  // namespace

void add_energy_bench_command(CLI::App* energy) {
    struct Args {
        std::vector<std::string> backends{"cpu"};
        std::string source, kernel = "sobel", size = "720p", platform, out = "energy-bench";
        std::string sysfs_root = "/sys", nvml_lib = "libnvidia-ml.so.1", vcgencmd = "/usr/bin/vcgencmd";
        int frames = 50, particles = 1000, repeat = 1;
        double period_ms = 2, idle_ms = 50, lead_idle_ms = 1000, sync_unit_ms = 0;
        std::size_t min_samples = 3;
        bool force = false, no_plots = false;
    };
    auto a = std::make_shared<Args>();
    auto* c = energy->add_subcommand("bench", "Run frames on each backend while sampling power in-process; report frames/s and J/frame per backend");
    c->add_option("--source", a->source, "Power source: hwmon:NAME[:CH], rapl:NAME or nvml:INDEX[:power|:energy] (energy sample --list)")->required();
    c->add_option("-b,--backend", a->backends, "Backends to run, in order (repeatable or comma-separated)")->delimiter(',')->capture_default_str();
    c->add_option("--kernel", a->kernel, "sobel or ncc")->capture_default_str()->check(CLI::IsMember({"sobel", "ncc"}));
    c->add_option("--size", a->size, "Sobel image size: 480p, 720p or 1080p")->capture_default_str()->check(CLI::IsMember(kFrameSizeNames));
    c->add_option("--particles", a->particles, "NCC: particles scored per frame")->capture_default_str()->transform(whole_in(1, kMaxParticles));
    c->add_option("-k,--frames", a->frames, "Frames per backend")->capture_default_str()->transform(whole_in(1, 1000000));
    c->add_option("--repeat", a->repeat, "Kernel calls per frame (frames shorter than a few sample periods cannot be measured alone)")
        ->capture_default_str()
        ->transform(whole_in(1, 100000));
    c->add_option("--period-ms", a->period_ms, "Sampling period (ms)")->capture_default_str()->check(real_in(0.05, 60000));
    c->add_option("--idle-ms", a->idle_ms, "Idle gap after each frame (ms)")->capture_default_str()->check(real_in(0, 600000));
    c->add_option("--lead-idle-ms", a->lead_idle_ms, "Idle baseline phase before and after each backend's frames (ms)")
        ->capture_default_str()
        ->check(real_in(0, 600000));
    c->add_option("--sync-unit-ms", a->sync_unit_ms, "Sync bursts 3u,1u,2u before the frames (ms; not needed on one clock)")
        ->capture_default_str()
        ->check(real_in(0, 60000));
    c->add_option("--min-samples", a->min_samples, "Frames with fewer power samples are flagged")->capture_default_str()->transform(whole_in(0, 1000000));
    c->add_option("--platform", a->platform, "Platform label (default: this host's name)");
    c->add_option("-o,--out", a->out, "Output folder")->capture_default_str();
    c->add_flag("--force", a->force, "Write into a non-empty folder that is not an earlier output of energy bench");
    c->add_flag("--no-plots", a->no_plots, "Skip the gnuplot figures");
    c->add_option("--sysfs-root", a->sysfs_root, "sysfs root for hwmon/rapl sources")->capture_default_str();
    c->add_option("--nvml-lib", a->nvml_lib, "NVML library to dlopen for nvml sources")->capture_default_str();
    c->add_option("--vcgencmd", a->vcgencmd, "vcgencmd program the pmic:vcgencmd source runs (absolute path)")->capture_default_str();
    c->callback([a] {
        // Everything is checked before the run, which takes minutes, and before the previous run's files are removed.
        const std::string platform = a->platform.empty() ? host_name() : a->platform;
        energy::check_label(platform, a->platform.empty() ? "this host's name (--platform's default)" : "--platform");
        io::check_output_folder(a->out, "energy bench", a->force);
        if (!a->no_plots && !io::gnuplot_available()) throw Error("energy bench: gnuplot not found (install it, or pass --no-plots)");
        std::set<std::string> seen;
        for (const auto& b : a->backends)
            if (!seen.insert(b).second) throw Error("--backend " + b + " is given twice");
        if (a->kernel == "ncc") limits::check_count("--particles", a->particles, limits::kMaxParticles, limits::kParticleBytes);
        energy::SamplerOptions so;
        so.sysfs_root = a->sysfs_root, so.nvml_library = a->nvml_lib, so.vcgencmd = a->vcgencmd;
        const auto sampler = energy::make_power_sampler(a->source, so);
        std::vector<std::unique_ptr<Backend>> backends;
        std::vector<energy::BenchTarget> targets;
        for (const auto& b : a->backends) backends.push_back(default_registry().create(b));
        for (std::size_t i = 0; i < backends.size(); ++i) {
            FrameWorkload w = make_frame_workload(*backends[i], a->kernel, a->size, a->particles);
            w.meta["repeat"] = std::to_string(a->repeat);
            auto once = std::move(w.kernel);
            auto kernel = a->repeat == 1 ? once : [once, n = a->repeat] {
                PhaseTimes sum;
                for (int k = 0; k < n; ++k) {
                    const PhaseTimes t = once();
                    sum.upload_ms += t.upload_ms, sum.execute_ms += t.execute_ms, sum.download_ms += t.download_ms;
                }
                return sum;
            };
            targets.push_back({a->backends[i], std::move(kernel), std::move(w.meta)});
        }
        energy::BenchConfig cfg;
        cfg.run.frames = a->frames, cfg.run.idle_s = a->idle_ms / 1000, cfg.run.lead_idle_s = a->lead_idle_ms / 1000;
        cfg.run.sync_unit_s = a->sync_unit_ms / 1000;
        cfg.period_s = a->period_ms / 1000;
        cfg.platform = platform;
        cfg.integration.min_samples = a->min_samples;
        cfg.calls_per_frame = a->repeat;
        std::fprintf(stderr, "energy bench: %zu backend(s) x %d frames, sampling %s every %g ms\n", targets.size(), a->frames,
                     sampler->describe().c_str(), a->period_ms);
        const energy::BenchResult res = energy::run_energy_bench(*sampler, targets, cfg);

        io::open_output_folder(a->out, "energy bench", a->force, "--out", io::Rerun::ReplacesPrevious);
        const std::string dir = a->out + "/";
        write_text_file(dir + "power.log", energy::format_trnkit_power(res.trace));
        for (const auto& r : res.rows) {
            const std::string name = io::plain_basename(r.target);
            write_text_file(dir + "markers-" + name + ".csv", energy::format_markers(r.markers));
            write_text_file(dir + "run-" + name + ".json", energy::run_report_json(r.run));
        }
        const std::string md = energy::bench_markdown(res);
        write_text_file(dir + "bench.md", md);
        write_text_file(dir + "bench.csv", energy::bench_csv(res));
        write_text_file(dir + "bench.json", energy::bench_json(res));
        std::cout << md << "\nwrote " << dir << "{bench.md,bench.csv,bench.json,power.log,markers-*.csv,run-*.json}\n";
        if (a->no_plots) return;
        energy::plot_bench(res, a->out);
        for (const auto& r : res.rows) energy::plot_power_trace(around(res.trace, r.markers), r.run, dir + "trace-" + io::plain_basename(r.target) + ".png");
        std::cout << "plots: " << dir << "{bench_energy,bench_speed,trace-*}.png\n";
    });
}

}  // namespace trn::cli
