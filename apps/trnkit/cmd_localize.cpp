// `trnkit localize`: runs the DPC-PFL particle filter over an AIR flight folder and writes the
// per-step CSV, the summary JSON and the plots (trajectories on the map, error over distance).
#include <charconv>
#include <cmath>
#include <cstdio>
#include <optional>
#include <utility>
#include <vector>
#include <filesystem>
#include <iostream>

#include "backend_env.hpp"
#include "commands.hpp"
#include "field_flags.hpp"
#include "filter_model_options.hpp"
#include "heading_options.hpp"
#include "mavlink_option.hpp"
#include "odometry_option.hpp"
#include "options.hpp"
#include "photo_import_options.hpp"
#include "progress.hpp"
#include "trn/io/image_header.hpp"
#include "trn/error.hpp"
#include "trn/registry.hpp"
#include "trn/filter/nadir_warp.hpp"
#include "trn/io/output_folder.hpp"
#include "trn/localize/air_inputs.hpp"
#include "trn/localize/gps_track.hpp"
#include "trn/localize/localization.hpp"
#include "trn/localize/localizer_defaults.hpp"
#include "trn/localize/localizer_settings.hpp"
#include "trn/localize/report_folder.hpp"
#include "trn/sim/air_format.hpp"
#include "trn/sim/map.hpp"
#include "trn/detail/angles.hpp"

namespace trn::cli {
namespace {

struct LocalizeArgs {
    localize::AirInputOptions inputs;  // dataset, map, resolution, camera, fps
    // Every default from the library's one home (trn/localize/localizer_defaults.hpp), which the C
    // API and Python take too.
    std::string backend = localize::kDefaultBackend, conversion = filter::FilterConfig{}.conversion.to_string(),
                sampling = filter::to_string(filter::FilterConfig{}.sampling), out;
    std::string odometry;  // folder (SvoX/SvoY columns) | visual (from the frames)
    std::uint64_t seed = filter::FilterConfig{}.seed;
    double rate_hz = localize::kDefaultRateHz, sparse = 1;
    double max_tilt_deg = localize::LocalizerConfig{}.max_tilt_deg;
    // Defaults: the profile's (ours: 1000, 100, 2000; dissertation: 500, 100, its safety cap);
    // an option given replaces it.
    std::size_t particles = filter::FilterConfig{}.fixed_particles, min_particles = filter::FilterConfig{}.min_particles,
                max_particles = filter::FilterConfig{}.max_particles;
    const CLI::Option *particles_given = nullptr, *min_given = nullptr, *max_given = nullptr, *init_radius_given = nullptr;
    int template_width = localize::LocalizerConfig{}.scoring.template_width;
    // Start prior: kHandoverInitRadiusM (a GNSS-loss handover); --profile dissertation takes the
    // text's 300 m unless --init-radius-m is given.
    double init_radius_m = localize::kHandoverInitRadiusM, reinit_radius_m = filter::FilterConfig{}.reinit_radius_m, heading_sd_deg = NAN,
           start_heading_deg = NAN;
    std::string start, start_latlon;  // "X,Y" map px / "LAT,LON" degrees, checked at parse time
    double start_from_gps_m = 0;      // > 0: start at the first row's GPS fix within this radius (replaces --init-radius-m)
    bool no_plots = false, force = false;
    FilterModelArgs model;
    HeadingArgs heading;
    // --photos DIR: imported into --dataset first (import-photos), then localized from it.
    std::string photos;
    PhotoImportArgs photo;
    bool odometry_given = false, heading_given = false;
    std::string photo_options_given;  // the first import option given (they need --photos)
    MavlinkArgs mavlink;              // --mavlink: estimates streamed out as they come
    bool print_config = false;        // --print-config: the settings as JSON, then stop
};

// "A,B" as two finite reals, or nothing.
std::optional<std::pair<double, double>> parse_pair(const std::string& text) {
    const std::size_t comma = text.find(',');
    if (comma == std::string::npos) return std::nullopt;
    double v[2];
    const std::string parts[2] = {text.substr(0, comma), text.substr(comma + 1)};
    for (int i = 0; i < 2; ++i) {
        const auto [ptr, ec] = std::from_chars(parts[i].data(), parts[i].data() + parts[i].size(), v[i]);
        if (parts[i].empty() || ec != std::errc() || ptr != parts[i].data() + parts[i].size() || !std::isfinite(v[i])) return std::nullopt;
    }
    return std::pair{v[0], v[1]};
}

// CLI11 check: two comma-separated reals, the first within [lo1, hi1], the second within [lo2, hi2].
CLI::Validator pair_in(double lo1, double hi1, double lo2, double hi2, const std::string& what) {
    return CLI::Validator(
        [=](std::string& text) -> std::string {
            const auto p = parse_pair(text);
            if (!p) return "expected " + what + " (two numbers separated by a comma), got '" + text.substr(0, 40) + "'";
            if (p->first < lo1 || p->first > hi1 || p->second < lo2 || p->second > hi2)
                return text.substr(0, 40) + " is outside [" + std::to_string(lo1) + ", " + std::to_string(hi1) + "] x [" +
                       std::to_string(lo2) + ", " + std::to_string(hi2) + "]";
            return "";
        },
        what);
}

void progress_bar(std::size_t done, std::size_t total) { draw_progress(done, total, "steps"); }

bool georeferenced_map_file(const std::string& map) {
    const std::string ext = std::filesystem::path(map).extension().string();
    return ext == ".tif" || ext == ".tiff" || ext == ".TIF" || ext == ".TIFF";
}

// `--photos DIR`, before anything is read: photos carry no odometry and no compass, so visual
// odometry and --heading none (anything else is refused by name), and the first GPS fix is the
// start when the map can place it.
void apply_photo_defaults(LocalizeArgs& a, double init_radius_m) {
    if (a.odometry_given && a.odometry != "visual")
        throw Error("--odometry " + a.odometry + ": photos carry no recorded odometry; with --photos the odometry is visual");
    if (a.heading_given && a.heading.heading != "none")
        throw Error("--heading " + a.heading.heading + ": photos carry no compass heading; with --photos the heading is none");
    if (a.inputs.map.empty()) throw Error("--photos: needs --map (the orthophoto to localize the photos on)");
    a.odometry = "visual";
    a.heading.heading = "none";
    if (!a.start.empty() || !a.start_latlon.empty() || a.start_from_gps_m > 0) return;
    if (a.photo.map_origin.empty() && !georeferenced_map_file(a.inputs.map))
        throw Error("--photos: give --start X,Y (the first photo's map pixel), or a georeferenced map (a GeoTIFF, or --map-origin "
                    "LAT,LON) so that the first photo's GPS fix is the start");
    a.start_from_gps_m = init_radius_m;
    std::cerr << "trnkit: note: --photos: starting within --init-radius-m " << init_radius_m << " m of the first photo's GPS fix\n";
}

// `--dataset DIR` whose rows carry no heading (ImuX..W empty: an import-photos folder, a camera
// without a compass) and neither --heading nor --start-heading-deg: a compass filter would have no
// heading to score at (the Localizer refuses it), so the run is compass-less, as --photos is, and
// says so. Judged on the first row; an unreadable folder is left to the full read's error.
void apply_headingless_dataset_default(LocalizeArgs& a) {
    if (a.heading_given || !std::isnan(a.start_heading_deg) || a.inputs.dataset.empty()) return;
    sim::AirRecord first;
    try {
        sim::AirReader reader(a.inputs.dataset);
        if (!reader.next(first) || !std::isnan(first.imu.w)) return;
    } catch (const Error&) {
        return;
    }
    a.heading.heading = "none";
    std::cerr << "trnkit: note: " << a.inputs.dataset << " has no heading (ImuX..W empty): localizing without a compass "
              << "(--heading none); give --start-heading-deg to use a compass filter with that heading\n";
}

// The import into --dataset (an import-photos folder: replaced whole or not at all; its localize/
// output stays), after every check of the options.
void import_photos_into_dataset(LocalizeArgs& a) {
    sim::PhotoImportOptions& o = a.photo.o;
    o.photos = a.photos, o.out = a.inputs.dataset, o.map = a.inputs.map, o.metres_per_pixel = a.inputs.metres_per_pixel, o.force = a.force;
    try {
        run_photo_import(a.photo);
    } catch (const FieldError& e) {  // the import's own names for what localize calls --photos and --dataset
        if (e.field() == "photos") throw FieldError("--photos", e.detail());
        if (e.field() == "out") throw FieldError("dataset", e.detail());
        throw;
    }
    a.inputs.map.clear(), a.inputs.metres_per_pixel = 0;  // flight.json names them now
}

// The settings every option sets over the profile's preset (what --print-config prints): all but
// the map's resolution and the start, which come with the dataset.
localize::LocalizerConfig settings_of(const LocalizeArgs& a, localize::LocalizerConfig lc, bool dissertation) {
    lc.scoring.template_width = a.template_width;
    if (a.sparse < 1) lc.scoring.sampling = Sampling::random(a.sparse, a.seed);
    filter::FilterConfig& cfg = lc.filter;
    cfg.sampling = filter::parse_sampling_method(a.sampling);
    cfg.conversion = filter::Conversion::parse(a.conversion);
    cfg.seed = a.seed;
    cfg.reinit_radius_m = a.reinit_radius_m;
    if (!std::isnan(a.heading_sd_deg) || !dissertation) cfg.init_heading_sd_deg = a.heading_sd_deg;
    apply_filter_model_options(a.model, cfg);
    lc.max_tilt_deg = a.max_tilt_deg;
    lc.visual_odometry = a.odometry == "visual";  // the library's visual_odometry (run_localization runs it on the flight)
    lc.start_heading_rad = a.start_heading_deg * kDeg;
    apply_heading_options(a.heading, lc, !std::isnan(a.start_heading_deg) ? "--start-heading-deg" : !std::isnan(a.heading_sd_deg) ? "--heading-sd-deg" : "");
    return lc;
}

void localize(LocalizeArgs a) {
    if (a.photos.empty() && !a.photo_options_given.empty()) throw Error(a.photo_options_given + ": only with --photos (or import-photos)");
    std::vector<std::string> starts;
    for (const auto& [given, flag] : {std::pair{!a.start.empty(), "--start"}, {!a.start_latlon.empty(), "--start-latlon"}, {a.start_from_gps_m > 0, "--start-from-gps"}})
        if (given) starts.push_back(flag);
    if (starts.size() > 1)
        throw Error(starts[0] + (starts.size() == 3 ? ", " + starts[1] + " and " + starts[2] : " and " + starts[1]) + ": give one of them, not " +
                    (starts.size() == 3 ? "all three" : "both"));
    check_filter_model_options(a.model);
    // The profile's preset first (the library's defaults: localizer_defaults.hpp), then every option
    // that was given on top of it.
    localize::LocalizerConfig preset = localize::localizer_profile(filter::parse_profile(a.model.profile));
    filter::FilterConfig& profile = preset.filter;
    const bool dissertation = a.model.profile == "dissertation";
    if (a.particles_given->count() || !dissertation) profile.fixed_particles = a.particles;
    if (a.min_given->count() || !dissertation) profile.min_particles = a.min_particles;
    if (a.max_given->count() || !dissertation) profile.max_particles = a.max_particles;
    if (a.max_given->count()) preset.compassless_max_particles = 0;  // the count given is the count
    if (a.init_radius_given->count() || !dissertation) profile.init_radius_m = a.init_radius_m;
    if (!a.photos.empty()) apply_photo_defaults(a, profile.init_radius_m);
    else if (!a.print_config) apply_headingless_dataset_default(a);
    {
        // The most particles as the run will have them (the library's compass-less rule applied).
        localize::LocalizerConfig run = preset;
        if (a.heading.heading == "none") run.filter.heading = filter::HeadingMode::None, run.start_heading_rad = a.heading.start_yaw_deg * kDeg;
        const std::size_t max_particles = localize::resolved_config(run).filter.max_particles;
        if (profile.min_particles > max_particles)
            throw Error("--min-particles " + std::to_string(profile.min_particles) + " exceeds --max-particles " + std::to_string(max_particles) +
                        (dissertation ? " (--profile dissertation)" : ""));
    }
    const localize::LocalizerConfig settings = settings_of(a, preset, dissertation);
    if (a.print_config) {
        std::cout << localize::settings_json(settings, {{"backend", a.backend}, {"profile", a.model.profile}, {"odometry", a.odometry}},
                                             {{"rate_hz", a.rate_hz}})
                  << "\n";
        return;
    }
    if (a.inputs.dataset.empty()) throw CLI::RequiredError("--dataset");
    if (!a.photos.empty()) {
        // What the run will refuse, before the import replaces --dataset: the map (its header, within
        // the limits) and a --start on it.
        ImageSize map_size;
        try {
            map_size = check_image_file(a.inputs.map);
        } catch (const Error& e) {
            throw Error("--map " + std::string(e.what()));
        }
        if (!a.start.empty()) {
            const auto [x, y] = *parse_pair(a.start);
            if (!(x >= 0 && x < double(map_size.width) && y >= 0 && y < double(map_size.height)))
                throw Error("--start " + a.start + ": map pixel " + std::to_string(x) + "," + std::to_string(y) + " is outside the " +
                            std::to_string(map_size.width) + "x" + std::to_string(map_size.height) + " px map " + a.inputs.map);
        }
        // Both folders before the import: the one it replaces, and the report's.
        io::check_output_folder(a.inputs.dataset, "import-photos", a.force, "--dataset");
        io::check_output_folder(a.out.empty() ? a.inputs.dataset + "/localize" : a.out, "localize", a.force);
        import_photos_into_dataset(a);
    }
    const localize::AirInputs in = localize::resolve_air_inputs(a.inputs);
    const std::string out = a.out.empty() ? a.inputs.dataset + "/localize" : a.out;
    // The default folder comes with the dataset: a link there was planted, not chosen.
    if (a.out.empty() && std::filesystem::is_symlink(out))
        throw Error(out + ": is a symbolic link inside the dataset; trnkit does not write through it (remove it, or give --out)");
    io::check_output_folder(out, "localize", a.force);  // before the run, not after it
    for (const localize::AirInputs::Note& n : in.notes)
        std::cerr << "trnkit: note: " << (n.field.empty() ? "" : flag_of(n.field) + " ") << flags_in(n.text) << "\n";
    const sim::Map& map = in.map;
    const std::string& dataset = a.inputs.dataset;
    const double mpp = map.metres_per_pixel;
    double start_x = NAN, start_y = NAN;  // NaN: the first row's MapX/MapY
    if (!a.start.empty()) std::tie(start_x, start_y) = *parse_pair(a.start);
    if (!a.start_latlon.empty()) {
        if (!in.to_map_pixel)
            throw Error("--start-latlon: " +
                        (in.has_flight_json ? dataset + "/flight.json has no geo origin and the map is no GeoTIFF"
                                            : "the map is no GeoTIFF and there is no flight.json with a geo origin") +
                        "; give --start X,Y in map pixels instead");
        const auto [lat, lon] = *parse_pair(a.start_latlon);
        const auto p = in.to_map_pixel(lat, lon);
        start_x = p[0], start_y = p[1];
    }
    // Camera GPS (import-photos): the first fix as the start, every fix as a reference track.
    const localize::GpsTrack gps = a.start_from_gps_m > 0 || in.latlon_source == sim::kLatLonCameraGps ? localize::read_gps_track(dataset)
                                                                                                     : localize::GpsTrack{};
    if (a.start_from_gps_m > 0) {
        const std::array<double, 2> p = localize::gps_start(gps, dataset, in.to_map_pixel);
        start_x = p[0], start_y = p[1];
    }
    const std::string start_text = !a.start.empty() ? "--start " + a.start : !a.start_latlon.empty() ? "--start-latlon " + a.start_latlon
                                                                                                      : "--start-from-gps (the first row's GPS fix)";
    if (std::isfinite(start_x) && !(start_x >= 0 && start_x < map.image.width && start_y >= 0 && start_y < map.image.height))
        throw Error(start_text + ": map pixel " + std::to_string(start_x) +
                    "," + std::to_string(start_y) + " is outside the " + std::to_string(map.image.width) + "x" +
                    std::to_string(map.image.height) + " px map");

    if (!a.mavlink.target.empty() && !in.to_latlon)  // before the run: every message carries latitude/longitude
        throw Error("--mavlink: needs latitude/longitude: " +
                    (in.has_flight_json ? dataset + "/flight.json has no geo origin and the map is no GeoTIFF"
                                        : "the map is no GeoTIFF and there is no flight.json with a geo origin"));
    std::unique_ptr<Backend> backend;
    if (a.backend == "fastest") {
        backend = default_registry().create_fastest(backend_options_from_environment());
    } else {
        backend = default_registry().create(a.backend, backend_options_from_environment());
    }
    localize::LocalizationSpec spec;
    spec.flight = localize::AirFolderFlight{dataset, in.camera, in.fps, a.max_tilt_deg, in.has_flight_json};
    spec.odometry = a.odometry == "visual" ? localize::OdometryKind::Visual : localize::OdometryKind::Recorded;
    spec.rate_hz = a.rate_hz;
    spec.to_latlon = in.to_latlon;
    localize::LocalizerConfig& lc = spec.localizer;
    lc = settings;
    filter::FilterConfig& cfg = lc.filter;
    cfg.metres_per_pixel = mpp;
    if (a.start_from_gps_m > 0) cfg.init_radius_m = a.start_from_gps_m;
    lc.start_x = start_x, lc.start_y = start_y;
    lc = localize::resolved_config(lc);  // as the Localizer will run it (and the report says)
    const bool compassless = cfg.heading == filter::HeadingMode::None;

    localize::RunHooks hooks;
    hooks.warning = [](const std::string& w) { std::cerr << "trnkit: warning: " << w << "\n"; };
    hooks.started = [&](const localize::RunInfo& run) {
        std::cerr << "localizing " << dataset << " (" << run.frames << " frames, every " << run.stride << ") on " << backend->info().name << ", "
                  << cfg.conversion.to_string() << ", " << filter::to_string(cfg.sampling) << " sampling, " << a.odometry << " odometry, "
                  << (compassless ? "no compass (yaw prior " + describe_yaw_prior(a.heading) + "), " : std::string()) << "seed " << a.seed << "\n";
    };
    hooks.progress = progress_bar;
    std::unique_ptr<MavlinkOut> mavlink;
    if (!a.mavlink.target.empty()) {
        mavlink = std::make_unique<MavlinkOut>(a.mavlink, mpp, compassless);
        hooks.step = [&](const localize::LocalizationRow& row, const localize::Estimate& e) { mavlink->step(row, e); };
    }
    const localize::LocalizationResult result = localize::run_localization(spec, map, *backend, hooks);
    const bool has_latlon = in.to_latlon && !result.rows.empty();

    localize::ReportOptions report;
    report.owner = "localize", report.folder_name = "--out", report.force = a.force, report.plots = !a.no_plots, report.plot_title = in.scenario;
    report.odometry = a.odometry;
    report.strings = {{"profile", a.model.profile}, {"backend_requested", a.backend}, {"dataset", dataset}, {"map", in.map_path},
                      {"start", a.start.empty() && a.start_latlon.empty() && !(a.start_from_gps_m > 0) ? "first row's MapX,MapY" : start_text},
                      {"start_heading", compassless ? "--heading none: yaw prior " + describe_yaw_prior(a.heading)
                                        : std::isnan(a.start_heading_deg) ? "first magnetometer reading" : "--start-heading-deg"},
                      {"flight_json", in.has_flight_json ? "used" : "absent (camera, map and resolution from options)"},
                      {"georeference", in.georeference.empty() ? "none" : in.georeference},
                      {"photos", a.photos.empty() ? "none" : a.photos + " (imported into the dataset first)"},
                      {"map_no_data", map.valid.width > 0 ? "masked (alpha, GeoTIFF mask or --nodata)" : "none"}};
    report.numbers = {{"init_radius_m", cfg.init_radius_m}, {"reinit_radius_m", cfg.reinit_radius_m},
                      {"start_x", result.run.start_x}, {"start_y", result.run.start_y}, {"particles", static_cast<double>(cfg.fixed_particles)},
                      {"min_particles", static_cast<double>(cfg.min_particles)}, {"max_particles", static_cast<double>(cfg.max_particles)},
                      {"rate_hz", a.rate_hz}, {"sparse", a.sparse}, {"metres_per_pixel", mpp},
                      {"start_heading_deg", a.start_heading_deg}, {"heading_sd_deg", cfg.init_heading_sd_deg},
                      {"camera_hfov_deg", in.camera.hfov_deg}, {"max_tilt_deg", a.max_tilt_deg},
                      {"final_estimate_lat", has_latlon ? result.rows.back().estimate_lat : NAN},
                      {"final_estimate_lon", has_latlon ? result.rows.back().estimate_lon : NAN}};
    if (compassless) report.numbers["start_yaw_deg"] = a.heading.start_yaw_deg, report.numbers["start_yaw_sd_deg"] = cfg.init_heading_sd_deg;
    if (has_latlon) {
        char ll[96];
        std::snprintf(ll, sizeof ll, "lat %.7f lon %.7f", result.rows.back().estimate_lat, result.rows.back().estimate_lon);
        report.after_summary = "final estimate: " + std::string(ll) + " (" + in.georeference + ")\n";
    }
    if (gps.camera_gps && !gps.fixes.empty() && in.to_map_pixel) {  // the camera's fixes beside the estimates
        const localize::GpsComparison c = localize::compare_with_gps(result, gps, in.to_map_pixel, mpp);
        report.files["gps_track.csv"] = c.csv;
        report.reference = {"camera GPS (reference, lags and drifts)", c.fix_px};
        report.strings["gps_reference"] = std::string("metadata.csv Latitude,Longitude: ") + localize::kCameraGpsCaveat;
        report.numbers["estimate_to_gps_mean_m"] = c.mean_m, report.numbers["estimate_to_gps_final_m"] = c.final_m;
        report.numbers["estimate_to_gps_max_m"] = c.max_m, report.numbers["gps_fixes_compared"] = static_cast<double>(c.compared);
        char line[200];
        std::snprintf(line, sizeof line, "estimate to camera GPS: mean %.1f m, final %.1f m, max %.1f m over %zu fixes (", c.mean_m, c.final_m,
                      c.max_m, c.compared);
        report.after_summary += line + std::string(localize::kCameraGpsCaveat) + ")\n";
    }
    if (mavlink) report.after_summary += mavlink->summary();
    localize::write_localization_report(result, out, map.image.view(), mpp, report, std::cout);
}

}  // namespace

void add_localize_command(CLI::App& app) {
    auto a = std::make_shared<LocalizeArgs>();
    auto* cmd = app.add_subcommand("localize", "Localize an AIR flight folder on its map with the DPC-PFL particle filter");
    cmd->add_option("--dataset", a->inputs.dataset,
                    "AIR flight folder (metadata.csv, frames; flight.json optional); with --photos: the AIR folder the photos are imported into "
                    "(required but with --print-config)");
    cmd->add_flag("--print-config", a->print_config,
                  "Print the settings (the profile's defaults and every option given) as one line of JSON under the names of "
                  "docs/EMBEDDING.md's defaults table, then exit without reading anything");
    cmd->add_option("--photos", a->photos,
                    "Folder of geotagged camera photos (JPEG + EXIF): imported into --dataset first (as import-photos does; needs --map and "
                    "--altitude-agl), then localized with visual odometry and no compass");
    add_photo_import_options(*cmd, a->photo);
    cmd->add_option("--map", a->inputs.map,
                    "Localization map image (default: the one flight.json names); a .tif/.tiff is read as a GeoTIFF (GDAL): "
                    "resolution and latitude/longitude from its georeference");
    cmd->add_option("--nodata", a->inputs.nodata,
                    "Map grey level (0..255) that marks no-data where every colour channel has it; transparent pixels "
                    "(alpha 0) and a GeoTIFF's nodata value or mask are no-data anyway. Samples on no-data are left out of the scores")
        ->transform(whole_in(0, 255));
    cmd->add_option("--mpp", a->inputs.metres_per_pixel, "Map resolution, metres per pixel (default: flight.json or the GeoTIFF)")->check(real_in(0, 1000, Open::low));
    cmd->add_option("--hfov-deg", a->inputs.hfov_deg, "Camera horizontal field of view, degrees (default: flight.json)")
        ->check(real_in(localize::kMinCameraHfovDeg, localize::kMaxCameraHfovDeg));  // the Localizer's range
    cmd->add_option("--focal-px", a->inputs.focal_px, "Camera focal length in pixels of frames --focal-width px wide (instead of --hfov-deg)")
        ->check(real_in(0, 1e6, Open::low));
    cmd->add_option("--focal-width", a->inputs.focal_width, "Frame width (px) that --focal-px refers to")->transform(whole_in(2, 16384));
    cmd->add_option("--fps", a->inputs.fps, "Camera frame rate (default: flight.json; without it every row is a filter step)")
        ->check(real_in(0, 1000, Open::low));
    cmd->add_option("--max-tilt-deg", a->max_tilt_deg,
                    "Frames whose measured roll/pitch (ImuX..W) tilt the camera further from nadir are skipped and counted; "
                    "smaller tilts are warped to nadir (10: there the level crop keeps over half the frame width; at 15 only a third)")
        ->capture_default_str()
        ->check(real_in(0, 89));
    cmd->add_option("--backend", a->backend, "Scoring backend (cpu, opencl:0, vulkan, ... or 'fastest': the first usable of GPU OpenCL, GPU Vulkan, cpu, other devices, always the same on one machine)")->capture_default_str();
    cmd->add_option("--conversion", a->conversion, "linear, softmax, rectifying:D or logistic:V")->capture_default_str();
    cmd->add_option("--sampling", a->sampling, "kld, importance or rejection")->capture_default_str();
    cmd->add_option("--seed", a->seed, "Random seed (a fixed seed reproduces a run exactly)")->capture_default_str()->transform(any_seed());
    a->particles_given = cmd->add_option("--particles", a->particles, "Particle count for importance / rejection sampling (--profile dissertation: 500)")
        ->capture_default_str()
        ->transform(whole_in(1, kMaxParticles));
    a->min_given = cmd->add_option("--min-particles", a->min_particles, "KLD sampling: fewest particles")->capture_default_str()->transform(whole_in(1, kMaxParticles));
    a->max_given = cmd->add_option("--max-particles", a->max_particles,
                                   "KLD sampling: most particles (and, with --profile ours, the initial set; 6000 with --heading none and a uniform "
                                   "yaw prior; dissertation: " + std::to_string(filter::kDissertationMaxParticles) +
                                       ", a safety cap, and a 500-particle initial set)")
        ->capture_default_str()
        ->transform(whole_in(1, kMaxParticles));
    cmd->add_option("--rate", a->rate_hz, "Filter rate in Hz (every fps/rate-th frame is used)")->capture_default_str()->check(real_in(0, 1000, Open::low));
    cmd->add_option("--template-width", a->template_width, "Camera frames are downscaled to this width before scoring ('full': not downscaled)")
        ->capture_default_str()
        ->transform(template_width_option());
    cmd->add_option("--sparse", a->sparse, "Share of template pixels scored (1 = dense)")->capture_default_str()->check(real_in(1e-4, 1.0));
    cmd->add_option("--out", a->out, "Output folder (default: DATASET/localize)");
    a->init_radius_given = cmd->add_option("--init-radius-m", a->init_radius_m,
                    "Particles start uniform within this radius (m) of the start; 50 m suits a handover after GNSS loss, "
                    "where the last fix is good to metres (the dissertation's 300 m assumes no fix; --profile dissertation takes it)")
        ->capture_default_str()
        ->check(real_in(0, 1e5, Open::low));
    cmd->add_option("--reinit-radius-m", a->reinit_radius_m, "Radius (m) of the re-initialisation around the last estimate when every weight collapses")
        ->capture_default_str()
        ->check(real_in(0, 1e5, Open::low));
    cmd->add_option("--start", a->start, "Start position X,Y in map pixels (default: the first row's MapX,MapY; required without them)")
        ->check(pair_in(0, 1e7, 0, 1e7, "X,Y"));
    cmd->add_option("--start-latlon", a->start_latlon, "Start position LAT,LON in degrees (needs a geo origin in flight.json)")
        ->check(pair_in(-90, 90, -180, 180, "LAT,LON"));
    cmd->add_option("--start-from-gps", a->start_from_gps_m,
                    "Start within this radius (m) of the first row's GPS fix (camera photos: import-photos); needs a georeferenced map "
                    "(GeoTIFF or flight.json origin); replaces --init-radius-m")
        ->check(real_in(0, 1e5, Open::low));
    cmd->add_option("--start-heading-deg", a->start_heading_deg, "Initial heading prior, degrees clockwise from north (default: the first magnetometer reading; with --heading none: --start-yaw-deg)")
        ->check(real_in(-360, 360));
    cmd->add_option("--heading-sd-deg", a->heading_sd_deg, "Spread (sd, degrees) of the initial headings (default: --motion-eps-rot; --profile dissertation: a third of it, one sample_normal)")
        ->check(real_in(0, 360));
    cmd->add_flag("--no-plots", a->no_plots, "Skip the gnuplot step");
    cmd->add_flag("--force", a->force, "Write into a non-empty folder that is not an earlier output of localize");
    add_odometry_option(*cmd, a->odometry, {"folder", "visual"},
                        "Odometry fed to the filter: folder (metadata.csv's SvoX/SvoY) or visual (computed from the frames)");
    add_filter_model_options(*cmd, a->model);
    add_heading_options(*cmd, a->heading);
    add_mavlink_options(*cmd, a->mavlink);
    cmd->callback([a, cmd] {
        a->odometry_given = cmd->count("--odometry") > 0, a->heading_given = cmd->count("--heading") > 0;
        for (const char* o : {"--altitude-agl", "--sensor-width-mm", "--ignore-orientation", "--map-origin"})
            if (cmd->count(o) > 0 && a->photo_options_given.empty()) a->photo_options_given = o;
        localize(*a);
    });
}

}  // namespace trn::cli
