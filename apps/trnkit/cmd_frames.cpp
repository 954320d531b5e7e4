// `trnkit frames`: the dissertation's Algorithm 3 as a tool. Runs K frames of Sobel (480p, 720p,
// 1080p) or NCC scoring (N particles) on one backend, with idle gaps and a sync pattern first,
// and writes the marker file `trnkit energy integrate` reads.
#include <cmath>
#include <algorithm>
#include <cstdio>
#include <iostream>
#include <random>
#include <vector>

#include "backend_env.hpp"
#include "commands.hpp"
#include "options.hpp"
#include "trn/energy/frame_runner.hpp"
#include "trn/error.hpp"
#include "trn/io/atomic_file.hpp"
#include "trn/limits.hpp"
#include "trn/registry.hpp"
#include "trn/scoring_plan.hpp"

namespace trn::cli {
namespace {

// A deterministic textured grey image (smooth blobs plus fine noise), so NCC has a clear peak
// and Sobel has real edges to work on.
std::vector<std::uint8_t> textured_image(int w, int h, std::uint32_t seed) {
    std::vector<std::uint8_t> px(static_cast<std::size_t>(w) * h);
    std::mt19937 rng(seed);
    std::uniform_int_distribution<int> noise(-20, 20);
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
            const double v = 128 + 60 * std::sin(x * 0.05) * std::cos(y * 0.07) + 30 * std::sin((x + 2 * y) * 0.013);
            px[static_cast<std::size_t>(y) * w + x] = static_cast<std::uint8_t>(std::clamp(v + noise(rng), 0.0, 255.0));
        }
    return px;
}

void size_of(const std::string& name, int& w, int& h) {
    if (name == "480p") w = 640, h = 480;
    else if (name == "720p") w = 1280, h = 720;
    else if (name == "1080p") w = 1920, h = 1080;
    else throw Error("--size '" + name + "': expected 480p, 720p or 1080p");
}

}  // namespace

void add_frames_command(CLI::App& app) {
    struct Args {
        std::string kernel = "sobel", size = "480p", backend = "cpu", out = "frames.csv";
        int frames = 100, particles = 1000;
        double idle_ms = 100, lead_idle_ms = 1000, sync_unit_ms = 100;
    };
    auto a = std::make_shared<Args>();
    auto* cmd = app.add_subcommand("frames", "Run a kernel K times with idle gaps and a sync pattern, writing frame markers (energy studies)");
    cmd->add_option("--kernel", a->kernel, "sobel or ncc")->capture_default_str()->check(CLI::IsMember({"sobel", "ncc"}));
    cmd->add_option("--size", a->size, "Sobel image size: 480p, 720p or 1080p")->capture_default_str();
    cmd->add_option("--particles", a->particles, "NCC: particles scored per frame")->capture_default_str()->transform(whole_in(1, kMaxParticles));
    cmd->add_option("-b,--backend", a->backend, "Backend: cpu-ref, cpu, opencl[:N|:name], vulkan[:N|:name]")->capture_default_str();
    cmd->add_option("-k,--frames", a->frames, "Frames (K)")->capture_default_str()->transform(whole_in(1, 1000000));
    cmd->add_option("--idle-ms", a->idle_ms, "Idle gap after each frame (ms)")->capture_default_str()->check(real_in(0, 600000));
    cmd->add_option("--lead-idle-ms", a->lead_idle_ms, "Idle before the sync pattern and after the last frame (ms)")
        ->capture_default_str()
        ->check(real_in(0, 600000));
    cmd->add_option("--sync-unit-ms", a->sync_unit_ms, "Sync pattern unit u: bursts of 3u,1u,2u (ms; 0 = none)")
        ->capture_default_str()
        ->check(real_in(0, 60000));
    cmd->add_option("-o,--out", a->out, "Marker file to write")->capture_default_str();
    cmd->callback([a] {
        if (a->particles <= 0) throw Error("--particles must be positive");
        io::check_output_file(a->out, "--out");  // before the run, which takes minutes
        limits::check_count("--particles", a->particles, limits::kMaxParticles, limits::kParticleBytes);
        auto backend = default_registry().create(a->backend, backend_options_from_environment());
        energy::FrameRunConfig cfg;
        cfg.frames = a->frames, cfg.idle_s = a->idle_ms / 1000, cfg.lead_idle_s = a->lead_idle_ms / 1000, cfg.sync_unit_s = a->sync_unit_ms / 1000;
        cfg.meta = {{"backend", backend->info().name}, {"device", backend->info().device}, {"kernel", a->kernel}};
        for (auto& [k, v] : cfg.meta)
            for (char& ch : v)
                if (ch == ' ' || ch == '=' || ch == ',') ch = '_';  // header is space-separated key=value
        energy::MarkerFile markers;
        if (a->kernel == "sobel") {
            int w = 0, h = 0;
            size_of(a->size, w, h);
            cfg.meta["size"] = a->size;
            const auto img = textured_image(w, h, 1);
            std::vector<std::int16_t> gx(img.size()), gy(img.size());
            markers = energy::run_frames([&] {
                PhaseTimes t;
                backend->sobel({img.data(), w, h, w}, {gx.data(), w, h, w}, {gy.data(), w, h, w}, &t);
                return t;
            }, cfg);
        } else {
            const int mw = 1024, mh = 1024, tw = 64, th = 64;
            cfg.meta["particles"] = std::to_string(a->particles);
            const auto map = textured_image(mw, mh, 2);
            std::vector<std::uint8_t> templ(static_cast<std::size_t>(tw) * th);
            for (int y = 0; y < th; ++y)
                for (int x = 0; x < tw; ++x) templ[static_cast<std::size_t>(y) * tw + x] = map[static_cast<std::size_t>(y + 480) * mw + x + 480];
            std::mt19937 rng(3);
            std::uniform_real_distribution<float> pos(200, 800), yaw(-0.3f, 0.3f), scale(0.9f, 1.1f);
            std::vector<Pose> poses(static_cast<std::size_t>(a->particles));
            for (auto& p : poses) p = {pos(rng), pos(rng), yaw(rng), scale(rng)};
            std::vector<ParticleScore> scores(poses.size());
            const MapHandle handle = backend->upload_map({map.data(), mw, mh, mw});
            const ScoringPlan plan = make_scoring_plan(TemplateView(GrayView{templ.data(), tw, th, tw}), ScoreOptions{});
            markers = energy::run_frames([&] {
                PhaseTimes t;
                backend->score(handle, plan, poses, scores, &t);
                return t;
            }, cfg);
        }
        io::write_file_atomic(a->out, energy::format_markers(markers));
        std::size_t frames = 0;
        double exec = 0;
        for (const auto& r : markers.rows)
            if (r.kind == "frame") ++frames, exec += r.exec_ms;
        std::printf("%s: %zu frames of %s on %s, mean exec %.3f ms -> %s\n", a->backend.c_str(), frames, a->kernel.c_str(),
                    backend->info().name.c_str(), exec / std::max<std::size_t>(frames, 1), a->out.c_str());
    });
}

}  // namespace trn::cli
