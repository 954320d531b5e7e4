// `trnkit register`: find the poses of consecutive real camera frames on a map (ground truth for a
// real AIR folder), or `--verify` a poses file: each pose must be the best NCC within +-R px.
#include <cstdio>
#include <filesystem>
#include <iostream>

#include "backend_env.hpp"
#include "commands.hpp"
#include "options.hpp"
#include "trn/error.hpp"
#include "trn/filter/frame_registration.hpp"
#include "trn/filter/real_air_folder.hpp"
#include "trn/io/map_pixels.hpp"
#include "trn/io/atomic_file.hpp"
#include "trn/io/output_folder.hpp"
#include "trn/io/image_io.hpp"
#include "trn/registry.hpp"
#include "trn/detail/angles.hpp"

namespace trn::cli {
namespace {

// The grid (step 2 px, half-resolution sparse template) puts its best point a few px from the
// dense optimum; farther than the shoulder of one peak means another peak wins.
constexpr double kBestTolerancePx = reg::kShoulderPx;

std::string row_text(const std::string& frame, const reg::FramePose& f, const reg::Uniqueness& u) {
    char buf[400];
    const Pose& p = f.pose;
    std::snprintf(buf, sizeof buf, "%s,%.2f,%.2f,%.5f,%.5f,%.4f,%.1f,%.1f,%.1f,%.1f,%.4f,%.1f,%.1f\n", frame.c_str(), p.x, p.y, p.yaw,
                  p.scale, u.ncc_at_pose, f.dx, f.dy, f.chain_dx, f.chain_dy, u.runner_up_ncc, u.runner_up_dist, u.best_dist);
    return buf;
}

// ncc: dense NCC at the pose (cpu backend); step_d*: refined minus the previous frame's pose moved
// by the frame motion; chain_d*: refined minus the joint chain; runner_up_*: the best other peak
// within the window (sparse NCC, distance from the pose); best_dist: the window's best from the pose.
const char* kHeader = "frame,x,y,yaw,scale,ncc,step_dx,step_dy,chain_dx,chain_dy,runner_up_ncc,runner_up_dist,best_dist\n";

}  // namespace

void add_register_command(CLI::App& app) {
    struct Args {
        std::string map, verify, out, backend = "cpu", air_out;
        std::uint64_t seed = 1;
        int nodata = -1;
        double mpp = 0.5, hfov_deg = 60, fps = 0.5;  // what --air-out's flight.json says (the first real flight's)
        bool force = false;
        std::vector<std::string> frames;
        double radius = 160, min_scale = 0.3, max_scale = 1.5;
        std::vector<double> anchor;
    };
    auto a = std::make_shared<Args>();
    auto* cmd = app.add_subcommand("register", "Find the poses of consecutive real frames on a map (or --verify a poses CSV)");
    cmd->add_option("--map", a->map, "Orthophoto the frames were taken over")->required();
    cmd->add_option("frames", a->frames, "Consecutive camera frames, in flight order")->required();
    cmd->add_option("--verify", a->verify, "Check this poses CSV instead of searching (rows name the frames by file name)");
    cmd->add_option("-o,--out", a->out, "Poses CSV to write (default: standard output); written even when a pose fails the check (exit status 1)");
    cmd->add_option("-b,--backend", a->backend, "Backend that scores NCC")->capture_default_str();
    cmd->add_option("--radius", a->radius, "Uniqueness window: each pose must be the best NCC within +-R map px")
        ->capture_default_str()
        ->check(real_in(4, 400));
    cmd->add_option("--min-scale", a->min_scale, "Smallest map px per frame px searched")->capture_default_str()->check(real_in(0.05, 4));
    cmd->add_option("--max-scale", a->max_scale, "Largest map px per frame px searched")->capture_default_str()->check(real_in(0.05, 4));
    cmd->add_option("--nodata", a->nodata,
                    "Map grey level (0..255) marking no-data where every colour channel has it (transparent pixels are no-data anyway)")
        ->transform(whole_in(0, 255));
    cmd->add_option("--anchor", a->anchor, "Approximate pose of the first frame X Y YAW_DEG SCALE: skips the global search")
        ->expected(4)
        ->check(real_in(-1e6, 1e6));
    cmd->add_option("--air-out", a->air_out,
                    "Also write an AIR folder of the frames with these poses as truth and simulated odometry and magnetometer "
                    "(only when every pose passes the check)");
    cmd->add_option("--mpp", a->mpp, "Map resolution, metres per pixel, written into --air-out's flight.json")
        ->capture_default_str()
        ->check(real_in(0, 1000, Open::low));
    cmd->add_option("--hfov-deg", a->hfov_deg, "Camera horizontal field of view for --air-out (turns the found scales into altitudes)")
        ->capture_default_str()
        ->check(real_in(1, 170, Open::both));
    cmd->add_option("--fps", a->fps, "Frame rate for --air-out's time stamps")->capture_default_str()->check(real_in(0, 1000, Open::low));
    cmd->add_flag("--force", a->force, "Write --air-out into a non-empty folder that is not an earlier register output (its other files stay)");
    cmd->add_option("--seed", a->seed, "Seed of the simulated odometry and magnetometer of --air-out")->capture_default_str()->check(any_seed());
    cmd->callback([a] {
        if (a->min_scale > a->max_scale) throw Error("--min-scale must not exceed --max-scale");
        if (!a->out.empty()) {
            std::vector<std::pair<std::string, std::string>> inputs{{"--map", a->map}, {"--verify", a->verify}};
            for (const std::string& f : a->frames) inputs.emplace_back("frame", f);
            io::check_output_is_not_input(a->out, "--out", inputs);
            io::check_output_file(a->out, "--out");
        }
        // An AIR folder is an output folder like any other: absent, empty or register's own.
        if (!a->air_out.empty()) io::check_output_folder(a->air_out, "register", a->force, "--air-out");
        const std::vector<reg::PoseRow> rows = a->verify.empty() ? std::vector<reg::PoseRow>{} : reg::read_pose_rows(a->verify);
        // Pixels and no-data as localize reads them (a GeoTIFF's mask and nodata value too).
        const io::MapPixels map_pixels = io::load_map_pixels(a->map, a->nodata >= 0 ? std::optional<int>(a->nodata) : std::nullopt);
        const GrayImage& map = map_pixels.image;
        const GrayImage& valid = map_pixels.valid;
        const GrayView valid_view = validity_view(valid);
        std::vector<GrayImage> frames;
        std::vector<std::string> names;
        for (const std::string& f : a->frames) {
            frames.push_back(load_gray(f));
            names.push_back(std::filesystem::path(f).filename().string());
        }
        auto backend = default_registry().create(a->backend, backend_options_from_environment());
        const MapHandle handle = backend->upload_map(map.view(), valid_view);

        std::string csv = kHeader;
        int failures = 0;
        std::vector<reg::PoseRow> found;  // in frame order, for --air-out
        std::vector<GrayImage> found_frames;
        auto check = [&](const std::string& name, const GrayImage& frame, const reg::FramePose& f) {
            const Pose& p = f.pose;
            const reg::Uniqueness u = reg::check_unique(*backend, handle, frame, p, a->radius, 2);
            const bool ok = u.best_dist <= kBestTolerancePx;
            if (!ok) ++failures;
            std::fprintf(stderr, "%s  x %7.1f y %7.1f yaw %6.1f deg scale %.3f  off chain %5.1f %5.1f  ncc %.3f  runner-up %.3f at %5.1f px%s\n", name.c_str(), p.x,
                         p.y, p.yaw * 180 / kPi, p.scale, f.chain_dx, f.chain_dy, u.ncc_at_pose, u.runner_up_ncc, u.runner_up_dist,
                         "");
            if (!ok) std::fprintf(stderr, "    NOT THE BEST: NCC %.3f at x %.1f y %.1f\n", u.best_ncc, u.best.x, u.best.y);
            csv += row_text(name, f, u);
            found.push_back({name, p, u.ncc_at_pose});
            found_frames.push_back(frame);
        };

        if (!a->verify.empty()) {
            for (const reg::PoseRow& row : rows) {
                std::size_t k = 0;
                while (k < names.size() && names[k] != row.frame) ++k;
                if (k == names.size()) throw Error(a->verify + ": frame '" + row.frame + "' is not among the given frames");
                check(row.frame, frames[k], reg::FramePose{row.pose});
            }
        } else {
            reg::RegisterOptions o;
            o.min_scale = a->min_scale;
            o.max_scale = a->max_scale;
            if (!a->anchor.empty()) {
                if (!(a->anchor[3] > 0)) throw Error("--anchor: SCALE must be positive");
                o.anchor_hint = Pose{static_cast<float>(a->anchor[0]), static_cast<float>(a->anchor[1]),
                                     static_cast<float>(a->anchor[2] * kPi / 180), static_cast<float>(a->anchor[3])};
            }
            const reg::Registration r = reg::register_frames(*backend, map, frames, names, o, valid_view);
            for (std::size_t k = 0; k + 1 < frames.size(); ++k)
                std::fprintf(stderr, "motion %s -> %s: rotation %6.2f deg, fitted scale %.4f (not used), shift %6.1f %6.1f px, %d inliers\n",
                             names[k].c_str(), names[k + 1].c_str(), r.motions[k].next_to_this.angle() * 180 / kPi,
                             r.motions[k].fitted_scale, r.motions[k].next_to_this.tx, r.motions[k].next_to_this.ty,
                             r.motions[k].inliers);
            for (std::size_t k = 0; k < frames.size(); ++k)
                std::fprintf(stderr, "chain %s: rotation %6.2f deg, scale %.4f, shift %7.1f %7.1f frame-0 px\n", names[k].c_str(),
                             r.chain[k].angle() * 180 / kPi, r.chain[k].scale(), r.chain[k].tx, r.chain[k].ty);
            std::fprintf(stderr, "anchor x %.1f y %.1f yaw %.2f deg scale %.4f, mean NCC of the chained poses %.3f\n", r.anchor.x, r.anchor.y,
                         r.anchor.yaw * 180 / kPi, r.anchor.scale, r.joint_ncc);
            for (std::size_t k = 0; k < frames.size(); ++k)
                check(names[k], frames[k], r.frames[k]);
        }
        if (a->out.empty()) std::cout << csv;
        else io::write_file_atomic(a->out, csv);
        if (!a->air_out.empty() && !failures) {
            reg::RealAirOptions o;
            o.metres_per_pixel = a->mpp, o.hfov_deg = a->hfov_deg, o.fps = a->fps;
            o.odometry.seed = a->seed;
            o.magnetometer.seed = a->seed + 1;
            io::open_output_folder(a->air_out, "register", a->force, "--air-out", io::Rerun::ReplacesPrevious);
            reg::write_real_air_folder(a->air_out, found, found_frames, o);
            std::cerr << "AIR folder " << a->air_out << ": " << found.size() << " frames\n";
        }
        if (failures) throw Error(std::string(a->air_out.empty() ? "" : "no AIR folder written: ") + std::to_string(failures) + " pose(s) are not the best NCC within +-" + std::to_string(int(a->radius)) + " px");
    });
}

}  // namespace trn::cli
