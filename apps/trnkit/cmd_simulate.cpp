// `trnkit simulate`: flies a scenario over a map (an orthophoto file or a procedural one) and writes
// an AIR flight folder: frames, metadata.csv, flight.json and the localization map. `--read DIR`
// reads a flight folder back and checks every row and image.
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <optional>

#include "commands.hpp"
#include "options.hpp"
#include "progress.hpp"
#include "trn/error.hpp"
#include "trn/io/output_folder.hpp"
#include "trn/sim/air_format.hpp"
#include "trn/sim/flight.hpp"
#include "trn/sim/map_ageing.hpp"
#include "trn/sim/procedural_map.hpp"

namespace trn::cli {
namespace {

struct SimulateArgs {
    std::string scenario, map, procedural, out, read;
    double mpp = 0, lat = NAN, lon = NAN, seconds = 0, fov = 60, noise = 0.02, wobble_deg = 0, size_m = 0;
    std::uint64_t seed = 1;
    int map_year = 0, base_year = 2008;
    std::size_t frames = 0;
    bool force = false;
};

void progress(std::size_t done, std::size_t total) { draw_progress(done, total, "frames"); }

// Builds the localization map (what a navigator would have on board) and the map the frames are
// rendered from (the world at flight time, aged when --map-year differs from the base year).
void make_maps(const SimulateArgs& a, const sim::FlightConfig& cfg, sim::Map& base, sim::Map& world, int& world_year) {
    world_year = a.map_year ? a.map_year : a.base_year;
    if (!a.map.empty()) {
        if (!(a.mpp > 0)) throw Error("--map needs --mpp (ground resolution in metres per pixel)");
        std::optional<sim::GeoOrigin> origin;
        if (!std::isnan(a.lat) || !std::isnan(a.lon)) {
            if (std::isnan(a.lat) || std::isnan(a.lon)) throw Error("--lat and --lon go together");
            origin = sim::GeoOrigin{a.lat, a.lon};
        }
        base = sim::load_map(a.map, a.mpp, origin);
        if (world_year != a.base_year) {
            sim::MapAgeingOptions ageing;
            ageing.years = std::abs(world_year - a.base_year);
            ageing.seed = a.seed;
            world = sim::age_map(base, ageing);
        } else {
            world = base;
        }
        return;
    }
    sim::ProceduralMapOptions o;
    o.style = a.procedural.empty() ? cfg.scenario.terrain : sim::parse_terrain_style(a.procedural);
    o.seed = a.seed;
    o.year = a.base_year;
    o.metres_per_pixel = a.mpp > 0 ? a.mpp : 1.0;
    // Big enough for the scenario's loop plus the camera footprint at its highest altitude, unless given.
    o.width_m = o.height_m = a.size_m > 0 ? a.size_m : sim::fitting_map_edge_m(cfg);
    if (!std::isnan(a.lat) && !std::isnan(a.lon)) o.origin = {a.lat, a.lon};
    o.validate();  // a bad size is one error line, not a progress line and then the error
    std::cerr << "generating a " << sim::to_string(o.style) << " map of " << o.width_m << " x " << o.height_m << " m at "
              << o.metres_per_pixel << " m/px (seed " << o.seed << ")\n";
    base = sim::generate_procedural_map(o);
    if (world_year != o.year) {
        o.year = world_year;
        world = sim::generate_procedural_map(o);
    } else {
        world = base;
    }
}

void simulate(const SimulateArgs& a) {
    if (a.out.empty()) throw Error("--out DIR is required");
    const sim::Scenario& preset = sim::find_scenario(a.scenario);
    sim::FlightConfig cfg;
    cfg.scenario = preset;
    cfg.camera.hfov_deg = a.fov;
    cfg.render.noise_sigma = a.noise;
    cfg.camera_roll_pitch_sd_deg = a.wobble_deg;
    cfg.seed = a.seed;
    if (a.frames && a.seconds > 0) throw Error("give --frames or --seconds, not both");
    cfg.frames = a.frames ? a.frames : a.seconds > 0 ? static_cast<std::size_t>(std::llround(a.seconds * preset.fps)) : 0;

    // The dataset is built whole in a staging folder next to --out and replaces it only when
    // complete: a failed or killed run leaves the earlier dataset as it was.
    io::StagedFolder staged(a.out, "simulate", a.force);
    const std::string dir = staged.path();
    sim::Map base, world;
    int world_year = 0;
    make_maps(a, cfg, base, world, world_year);
    sim::FlightSimulator flight(world, cfg);

    sim::AirWriter writer(dir);
    save_gray(dir + "/map.png", base.image.view());
    const auto t0 = std::chrono::steady_clock::now();
    const std::size_t total = flight.frame_count();
    sim::FlightFrame frame;
    char name[32];
    while (flight.next(frame)) {
        std::snprintf(name, sizeof name, "frame_%06zu.png", frame.index);
        writer.write(sim::make_air_record(frame, name), frame.image.view());
        if (frame.index % 10 == 0 || frame.index + 1 == total) progress(frame.index + 1, total);
    }
    writer.close();
    sim::FlightInfo info;
    info.scenario = preset.name;
    info.map_file = "map.png";
    info.metres_per_pixel = base.metres_per_pixel;
    info.origin = base.origin;
    info.camera = cfg.camera;
    info.fps = preset.fps;
    info.map_year = a.base_year;
    info.rendered_year = world_year;
    info.seed = a.seed;
    info.frames = total;  // `--read` refuses a metadata.csv with fewer rows
    sim::write_flight_info(dir + "/flight.json", info);
    staged.commit();
    const double s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    std::cout << preset.name << ": " << total << " frames (" << total / preset.fps << " s of flight) in " << s << " s -> "
              << a.out << "\n";
}

// Reads a flight folder back: every row parsed, every image present with the camera's size.
void read_back(const std::string& folder) {
    sim::FlightInfo info;
    const bool has_info = std::filesystem::exists(folder + "/flight.json");
    if (has_info) info = sim::read_flight_info(folder + "/flight.json");
    sim::AirReader reader(folder);
    sim::AirRecord r;
    std::size_t rows = 0;
    double path_m = 0, drift_m = 0, last_x = 0, last_y = 0;
    while (reader.next(r)) {
        if (has_info && info.frames && rows == info.frames)
            throw Error(reader.folder() + "/metadata.csv: more rows than the " + std::to_string(info.frames) + " frames flight.json declares");
        const GrayImage img = reader.load_image(r);
        if (has_info && (img.width != info.camera.width || img.height != info.camera.height))
            throw Error(reader.image_path(r) + ": " + std::to_string(img.width) + "x" + std::to_string(img.height) +
                        " differs from the camera in flight.json");
        if (rows) path_m += std::hypot(r.pose_m.x - last_x, r.pose_m.y - last_y);
        last_x = r.pose_m.x, last_y = r.pose_m.y;
        drift_m = std::hypot(r.svo_m.x - r.pose_m.x, r.svo_m.y - r.pose_m.y);
        ++rows;
    }
    if (has_info && info.frames && rows < info.frames)
        throw Error(folder + "/metadata.csv: " + std::to_string(rows) + " rows, but flight.json declares " + std::to_string(info.frames) +
                    " frames (an incomplete or cut dataset)");
    std::cout << folder << ": " << rows << " frames";
    if (has_info) std::cout << ", scenario " << info.scenario << ", map " << info.map_file << " at " << info.metres_per_pixel << " m/px";
    std::cout << ", path " << path_m << " m, final odometry error " << drift_m << " m\n";
}

}  // namespace

void add_simulate_command(CLI::App& app) {
    auto a = std::make_shared<SimulateArgs>();
    auto* cmd = app.add_subcommand("simulate", "Simulate a UAV flight over a map and write an AIR dataset (or --read one back)");
    cmd->add_option("--scenario", a->scenario, "Preset: FL-200 FL-300 FR-200 FR-300 FC-200 FC-300 UL-200 ... UC-300, each also as <name>-wind and <name>-long");
    cmd->add_option("--map", a->map, "Orthophoto file to fly over (any image OpenCV reads)");
    cmd->add_option("--mpp", a->mpp, "Map ground resolution, metres per pixel (required with --map; default 1 for procedural)")
        ->check(real_in(0, 1000, Open::low));
    cmd->add_option("--lat", a->lat, "Latitude of the map's top-left pixel")->check(real_in(-90, 90));
    cmd->add_option("--lon", a->lon, "Longitude of the map's top-left pixel")->check(real_in(-180, 180));
    cmd->add_option("--procedural", a->procedural, "Procedural map style: forest or urban (default: the scenario's terrain)");
    cmd->add_option("--size-m", a->size_m, "Procedural map edge, metres (default: fits the scenario)")->check(real_in(0, 20000, Open::low));
    cmd->add_option("--seed", a->seed, "Seed for the map, noise and sensors")->capture_default_str()->transform(any_seed());
    cmd->add_option("--map-year", a->map_year, "Render the frames from the map of this year (localize on the base year)")
        ->transform(whole_in(kMinYear, kMaxYear));
    cmd->add_option("--base-year", a->base_year, "Year of the localization map")->capture_default_str()->transform(whole_in(kMinYear, kMaxYear));
    auto* frames = cmd->add_option("--frames", a->frames, "Number of frames (default: the scenario's whole flight, 320 s; -long: Table 2.2's distance)")->transform(whole_in(1, 200000));
    cmd->add_option("--seconds", a->seconds, "Seconds of flight instead of --frames")->excludes(frames)->check(real_in(0, 4000, Open::low));
    cmd->add_option("--fov", a->fov, "Horizontal field of view, degrees")->capture_default_str()->check(real_in(1, 170, Open::both));
    cmd->add_option("--noise", a->noise, "Gaussian image noise, share of full scale")->capture_default_str()->check(real_in(0, 1));
    cmd->add_option("--wobble-deg", a->wobble_deg, "Camera roll/pitch wobble (0: gimbal-stabilised)")->capture_default_str()->check(real_in(0, 45));
    cmd->add_option("-o,--out", a->out, "Output flight folder");
    cmd->add_option("--read", a->read, "Read an AIR flight folder back and check it, instead of simulating");
    cmd->add_flag("--force", a->force, "Write into a non-empty folder that is not an earlier simulate output (its other files stay)");
    cmd->callback([a] {
        if (!a->read.empty()) return read_back(a->read);
        if (a->scenario.empty()) throw Error("--scenario is required (or --read DIR)");
        simulate(*a);
    });
}

}  // namespace trn::cli
