// `trnkit localize`: runs the DPC-PFL particle filter over an AIR flight folder and writes the
// per-step CSV, the summary JSON and the plots (trajectories on the map, error over distance).
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <iostream>

#include "commands.hpp"
#include "filter_model_options.hpp"
#include "options.hpp"
#include "progress.hpp"
#include "trn/error.hpp"
#include "trn/filter/backend_choice.hpp"
#include "trn/filter/flight_source.hpp"
#include "trn/filter/localization.hpp"
#include "trn/filter/report.hpp"
#include "trn/io/output_folder.hpp"
#include "trn/registry.hpp"
#include "trn/sim/air_format.hpp"
#include "trn/sim/map.hpp"

namespace trn::cli {
namespace {

struct LocalizeArgs {
    std::string dataset, map, backend = "fastest", conversion = "logistic:0.2", sampling = "kld", out;
    std::uint64_t seed = 1;
    double mpp = 0, rate_hz = 5, sparse = 1;
    std::size_t particles = 1000, min_particles = 100, max_particles = 2000;
    int template_width = 160;
    bool no_plots = false, force = false;
    FilterModelArgs model;
};

void progress_bar(std::size_t done, std::size_t total) { draw_progress(done, total, "steps"); }

void localize(const LocalizeArgs& a) {
    namespace fs = std::filesystem;
    check_filter_model_options(a.model);
    if (!fs::is_directory(a.dataset)) throw Error("--dataset " + a.dataset + ": not a folder");
    if (a.min_particles > a.max_particles)
        throw Error("--min-particles " + std::to_string(a.min_particles) + " exceeds --max-particles " + std::to_string(a.max_particles));
    const std::string info_path = a.dataset + "/flight.json";
    if (!fs::exists(info_path)) throw Error(info_path + ": missing (it names the camera and map resolution)");
    const std::string out = a.out.empty() ? a.dataset + "/localize" : a.out;
    io::check_output_folder(out, "localize", a.force);  // before the run, not after it
    const sim::FlightInfo info = sim::read_flight_info(info_path);
    const std::string map_path = !a.map.empty() ? a.map : info.map_file.empty() ? "" : a.dataset + "/" + info.map_file;
    if (map_path.empty()) throw Error("--map: flight.json names no map; give --map FILE");
    const double mpp = a.mpp > 0 ? a.mpp : info.metres_per_pixel;
    const sim::Map map = sim::load_map(map_path, mpp);

    std::unique_ptr<Backend> backend;
    if (a.backend == "fastest") {
        backend = filter::create_fastest_backend();
    } else {
        backend = default_registry().create(a.backend);
    }
    filter::BackendScorerOptions so;
    so.template_width = a.template_width;
    if (a.sparse < 1) so.sampling = Sampling::random(a.sparse, a.seed);
    filter::BackendScorer scorer(*backend, map.image.view(), so);

    filter::FilterConfig cfg;
    cfg.metres_per_pixel = mpp;
    cfg.sampling = filter::parse_sampling_method(a.sampling);
    cfg.conversion = filter::Conversion::parse(a.conversion);
    cfg.fixed_particles = a.particles;
    cfg.min_particles = a.min_particles;
    cfg.max_particles = a.max_particles;
    cfg.seed = a.seed;
    apply_filter_model_options(a.model, cfg);
    filter::ParticleFilter pf(scorer, cfg);

    if (!(a.rate_hz > 0)) throw Error("--rate must be > 0");
    const std::size_t stride = std::max<std::size_t>(1, static_cast<std::size_t>(std::lround(info.fps / a.rate_hz)));
    const std::size_t rows = filter::count_air_rows(a.dataset);
    filter::AirFlightSource source(a.dataset, info.camera, mpp, info.fps, stride, (rows + stride - 1) / stride,
                                   {map.image.width, map.image.height});
    for (const std::string& w : source.warnings()) std::cerr << "trnkit: warning: " << w << "\n";
    std::cerr << "localizing " << a.dataset << " (" << rows << " frames, every " << stride << ") on " << backend->info().name << ", "
              << cfg.conversion.to_string() << ", " << filter::to_string(cfg.sampling) << " sampling, seed " << a.seed << "\n";
    filter::LocalizationResult result;
    try {
        result = filter::run_localization(source, pf, progress_bar);
    } catch (const Error& e) {
        if (std::string(e.what()).rfind(a.dataset, 0) == 0) throw;  // the flight source's own errors name their place
        throw Error(source.position() + ": " + e.what());           // which row of the flight the library choked on
    }

    io::open_output_folder(out, "localize", a.force);
    filter::write_rows_csv(out + "/localization.csv", result.rows);
    filter::write_summary_json(out + "/summary.json", result.summary,
                               {{"backend", backend->info().name}, {"conversion", cfg.conversion.to_string()},
                                {"sampling", filter::to_string(cfg.sampling)}, {"dataset", a.dataset},
                                {"scoring_density", a.sparse < 1 ? "random " + std::to_string(a.sparse) : "dense"}},
                               filter::with_lock_numbers(result.summary, {{"seed", static_cast<double>(a.seed)}, {"filter_rate_hz", info.fps / stride},
                                {"template_width", static_cast<double>(a.template_width)}}));
    std::cout << filter::format_summary(result.summary) << filter::format_lock_summary(result.summary);
    std::cout << "per-step CSV: " << out << "/localization.csv\nsummary JSON: " << out << "/summary.json\n";
    if (!a.no_plots) {
        const filter::PlotFiles plots = filter::plot_run(out, result.rows, result.summary, map.image.view(), mpp, info.scenario);
        std::cout << "plots: " << plots.trajectory_png << " " << plots.error_png << "\n";
    }
}

}  // namespace

void add_localize_command(CLI::App& app) {
    auto a = std::make_shared<LocalizeArgs>();
    auto* cmd = app.add_subcommand("localize", "Localize an AIR flight folder on its map with the DPC-PFL particle filter");
    cmd->add_option("--dataset", a->dataset, "AIR flight folder (metadata.csv, frames, flight.json)")->required();
    cmd->add_option("--map", a->map, "Localization map image (default: the one flight.json names)");
    cmd->add_option("--mpp", a->mpp, "Map resolution, metres per pixel (default: flight.json)")->check(real_in(0, 1000, Open::low));
    cmd->add_option("--backend", a->backend, "Scoring backend (cpu, opencl:0, vulkan, ... or 'fastest')")->capture_default_str();
    cmd->add_option("--conversion", a->conversion, "linear, softmax, rectifying:D or logistic:V")->capture_default_str();
    cmd->add_option("--sampling", a->sampling, "kld, importance or rejection")->capture_default_str();
    cmd->add_option("--seed", a->seed, "Random seed (a fixed seed reproduces a run exactly)")->capture_default_str()->transform(any_seed());
    cmd->add_option("--particles", a->particles, "Particle count for importance / rejection sampling")
        ->capture_default_str()
        ->transform(whole_in(1, kMaxParticles));
    cmd->add_option("--min-particles", a->min_particles, "KLD sampling: fewest particles")->capture_default_str()->transform(whole_in(1, kMaxParticles));
    cmd->add_option("--max-particles", a->max_particles, "KLD sampling: most particles (and the initial set)")
        ->capture_default_str()
        ->transform(whole_in(1, kMaxParticles));
    cmd->add_option("--rate", a->rate_hz, "Filter rate in Hz (every fps/rate-th frame is used)")->capture_default_str()->check(real_in(0, 1000, Open::low));
    cmd->add_option("--template-width", a->template_width, "Camera frames are downscaled to this width before scoring")
        ->capture_default_str()
        ->transform(whole_in(8, kMaxTemplateWidth));
    cmd->add_option("--sparse", a->sparse, "Share of template pixels scored (1 = dense)")->capture_default_str()->check(real_in(1e-4, 1.0));
    cmd->add_option("--out", a->out, "Output folder (default: DATASET/localize)");
    cmd->add_flag("--no-plots", a->no_plots, "Skip the gnuplot step");
    cmd->add_flag("--force", a->force, "Write into a non-empty folder that is not an earlier output of localize");
    add_filter_model_options(*cmd, a->model);
    cmd->callback([a] { localize(*a); });
}

}  // namespace trn::cli
