// `trnkit demo`: what `./run demo` runs. Simulates a ~2 km flight over the built-in procedural map,
// rendered from the world two years after the localization map was taken, localizes it with the
// DPC-PFL particle filter on the fastest available backend, and prints the summary and the paths
// of the summary JSON and the plots. (The cross-backend scoring table is `trnkit check`.)
#include <sys/stat.h>
#include <unistd.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <iostream>

#include "backend_env.hpp"
#include "commands.hpp"
#include "filter_model_options.hpp"
#include "heading_options.hpp"
#include "odometry_option.hpp"
#include "options.hpp"
#include "progress.hpp"
#include "trn/error.hpp"
#include "trn/localize/localization.hpp"
#include "trn/localize/report_folder.hpp"
#include "trn/io/output_folder.hpp"
#include "trn/registry.hpp"
#include "trn/sim/procedural_map.hpp"

namespace trn::cli {
namespace {

struct DemoArgs {
    std::string scenario = "FR-200-wind", backend = "fastest", out;  // crab, climbs, barometer: scenario.hpp
    std::string odometry;  // simulated (default: the demo's figure stays) | visual
    double distance_km = NAN, rate_hz = 5, sparse = 1;  // NaN: 2 km, or a one_loop preset's own length
    double init_radius_m = filter::FilterConfig{}.init_radius_m;  // the dissertation's 300 m
    int template_width = 160;
    int map_year = 2008, flight_year = 2010;
    std::uint64_t seed = 1;
    bool no_plots = false, force = false;
    FilterModelArgs model;
    HeadingArgs heading;
    std::size_t max_particles = filter::FilterConfig{}.max_particles;
    const CLI::Option* max_particles_given = nullptr;
};

double seconds_since(std::chrono::steady_clock::time_point t0) {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

void progress_bar(std::size_t done, std::size_t total) { draw_progress(done, total, "steps"); }

void demo(const DemoArgs& a) {
    namespace fs = std::filesystem;
    check_filter_model_options(a.model);
    const auto t0 = std::chrono::steady_clock::now();
    const sim::Scenario& preset = sim::find_scenario(a.scenario);
    const double distance_km = std::isnan(a.distance_km) ? (preset.one_loop ? preset.distance_m() / 1000 : 2.0) : a.distance_km;
    if (!(distance_km > 0)) throw Error("--distance-km must be > 0");
    const std::string out = a.out.empty() ? (fs::temp_directory_path() / "trnkit-demo").string() : a.out;
    // The default folder is demo's by definition (older trnkit versions wrote it without a marker).
    const bool force = a.force || a.out.empty();
    if (a.out.empty()) {
        // The default lies in a shared temporary folder: one that is a link, or another user's, was
        // made by someone else.
        struct stat st {};
        if (::lstat(out.c_str(), &st) == 0 && (S_ISLNK(st.st_mode) || st.st_uid != ::geteuid()))
            throw Error(out + ": " + (S_ISLNK(st.st_mode) ? "is a symbolic link" : "belongs to another user") +
                        ", so it is not an earlier demo output of yours; give --out DIR");
    }
    io::check_output_folder(out, "demo", force);  // before the maps and the flight, not after

    // The localization map (a.map_year) and the world the camera sees (a.flight_year), same place.
    sim::ProceduralMapOptions mo;
    mo.style = preset.terrain;
    mo.seed = a.seed;
    mo.year = a.map_year;
    sim::FlightConfig fc;
    fc.scenario = preset;
    fc.seed = a.seed;
    fc.frames = static_cast<std::size_t>(std::llround(distance_km * 1000 / preset.speed_mps * preset.fps));
    mo.width_m = mo.height_m = sim::fitting_map_edge_m(fc);
    std::cerr << "generating the " << sim::to_string(mo.style) << " map (" << mo.width_m << " m square, " << a.map_year
              << ") and the world " << a.flight_year - a.map_year << " years later\n";
    const sim::Map map = sim::generate_procedural_map(mo);
    mo.year = a.flight_year;
    const sim::Map world = sim::generate_procedural_map(mo);
    const double maps_s = seconds_since(t0);

    std::vector<BackendTiming> timings;
    std::unique_ptr<Backend> backend;
    if (a.backend == "fastest") {
        backend = default_registry().create_fastest(backend_options_from_environment(), &timings);
    } else {
        backend = default_registry().create(a.backend, backend_options_from_environment());
    }
    std::cerr << "scoring on " << backend->info().name << " (" << backend->info().device << ")";
    if (!timings.empty()) {
        std::cerr << "; 1000-particle batch:";
        for (const auto& t : timings) std::cerr << " " << t.name << " " << t.score_ms << " ms";
    }
    std::cerr << "\n";

    localize::LocalizationSpec spec;
    spec.flight = localize::SimulatedFlight{&world, fc};
    spec.odometry = a.odometry == "visual" ? localize::OdometryKind::Visual : localize::OdometryKind::Recorded;
    spec.rate_hz = a.rate_hz;
    localize::LocalizerConfig& lc = spec.localizer;  // the dissertation's choices: KLD sampling, logistic:0.2
    lc.scoring.template_width = a.template_width;
    if (a.sparse < 1) lc.scoring.sampling = Sampling::random(a.sparse, a.seed);
    lc.filter = filter::profile_config(filter::parse_profile(a.model.profile));
    lc.filter.metres_per_pixel = map.metres_per_pixel;
    lc.filter.seed = a.seed;
    lc.filter.init_radius_m = a.init_radius_m;
    apply_filter_model_options(a.model, lc.filter);
    if (a.max_particles_given->count() || a.model.profile == "ours") lc.filter.max_particles = a.max_particles;
    if (lc.filter.min_particles > lc.filter.max_particles)
        throw Error("--max-particles " + std::to_string(lc.filter.max_particles) + " is below the " + std::to_string(lc.filter.min_particles) + " fewest particles");
    apply_heading_options(a.heading, lc);
    localize::RunHooks hooks;
    hooks.progress = progress_bar;
    const localize::LocalizationResult result = localize::run_localization(spec, map.image.view(), map.metres_per_pixel, *backend, hooks);

    std::cout << "DPC-PFL demo: " << preset.name << ", " << distance_km << " km at " << preset.altitude_m
              << (preset.other_altitude_m > 0 ? " and " + std::to_string(static_cast<int>(preset.other_altitude_m)) : std::string()) << " m, map "
              << a.flight_year - a.map_year << " years older than the flight, backend " << backend->info().name << ", seed " << a.seed
              << "\n";
    localize::ReportOptions report;
    report.owner = "demo", report.folder_name = "--out", report.force = force, report.plots = !a.no_plots, report.plot_title = preset.name;
    report.odometry = a.odometry;
    report.strings = {{"scenario", preset.name}, {"profile", a.model.profile}};
    report.numbers = {{"map_year", static_cast<double>(a.map_year)}, {"flight_year", static_cast<double>(a.flight_year)},
                      {"init_radius_m", a.init_radius_m}};
    if (lc.filter.max_particles != filter::FilterConfig{}.max_particles) report.numbers["max_particles"] = static_cast<double>(lc.filter.max_particles);
    if (a.heading.heading == "none") {
        report.strings["start_heading"] = "--heading none: yaw prior " + describe_yaw_prior(a.heading);
        report.numbers["start_yaw_deg"] = a.heading.start_yaw_deg, report.numbers["start_yaw_sd_deg"] = lc.filter.init_heading_sd_deg;
    }
    localize::write_localization_report(result, out, map.image.view(), map.metres_per_pixel, report, std::cout);
    std::printf("total %.1f s (maps %.1f s)\n", seconds_since(t0), maps_s);
}

}  // namespace

void add_demo_command(CLI::App& app) {
    auto a = std::make_shared<DemoArgs>();
    auto* cmd = app.add_subcommand("demo", "Simulate a ~2 km flight over the built-in procedural map and localize it (DPC-PFL)");
    cmd->add_option("--scenario", a->scenario, "Scenario preset (terrain, shape, altitude; -wind, -long twins)")->capture_default_str();
    cmd->add_option("--distance-km", a->distance_km, "Distance to fly (default: 2, or a -long preset's whole flight)")
        ->check(real_in(0, 100, Open::low));
    cmd->add_option("--backend", a->backend, "Scoring backend or 'fastest'")->capture_default_str();
    cmd->add_option("--rate", a->rate_hz, "Filter rate in Hz")->capture_default_str()->check(real_in(0, 1000, Open::low));
    cmd->add_option("--template-width", a->template_width, "Camera frames are downscaled to this width before scoring ('full': not downscaled)")
        ->capture_default_str()
        ->transform(template_width_option());
    cmd->add_option("--sparse", a->sparse, "Share of template pixels scored (1 = dense)")->capture_default_str()->check(real_in(1e-4, 1.0));
    cmd->add_option("--map-year", a->map_year, "Year of the localization map")->capture_default_str()->transform(whole_in(kMinYear, kMaxYear));
    cmd->add_option("--flight-year", a->flight_year, "Year the flight sees")->capture_default_str()->transform(whole_in(kMinYear, kMaxYear));
    cmd->add_option("--init-radius-m", a->init_radius_m,
                    "Particles start uniform within this radius (m) of the true start (300 m: the dissertation's, no fix; "
                    "50 m: a handover after GNSS loss, localize's default)")
        ->capture_default_str()
        ->check(real_in(0, 1e5, Open::low));
    cmd->add_option("--seed", a->seed, "Seed of map, flight and filter")->capture_default_str()->transform(any_seed());
    cmd->add_option("--out", a->out, "Output folder (default: <temp>/trnkit-demo)");
    cmd->add_flag("--no-plots", a->no_plots, "Skip the gnuplot step");
    cmd->add_flag("--force", a->force, "Write into a non-empty folder that is not an earlier output of demo");
    add_odometry_option(*cmd, a->odometry, {"simulated", "visual"},
                        "Odometry fed to the filter: simulated (statistical drift, sim/sensors.hpp) or visual (computed from the frames)");
    add_filter_model_options(*cmd, a->model);
    add_heading_options(*cmd, a->heading);
    a->max_particles_given = cmd->add_option("--max-particles", a->max_particles,
                                             "KLD sampling: most particles (and, with --profile ours, the initial set; dissertation: " +
                                                 std::to_string(filter::kDissertationMaxParticles) + ", a safety cap, and a 500-particle initial set)")
        ->capture_default_str()
        ->transform(whole_in(1, kMaxParticles));
    cmd->callback([a] { demo(*a); });
}

}  // namespace trn::cli
