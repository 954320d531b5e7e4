// `trnkit check`: a quick cross-backend run on built-in data: a synthetic textured map (or the real orthophoto when
// --map is given), one template cut from it at a known pose, N particles scored on every available
// backend, and a 1080p Sobel; it prints one table and checks every backend agrees with cpu-ref.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <iostream>
#include <numbers>
#include <random>

#include "backend_env.hpp"
#include "commands.hpp"
#include "options.hpp"
#include "trn/io/image_io.hpp"
#include "trn/registry.hpp"

namespace trn::cli {
namespace {

// A deterministic textured map: sums of sines at several scales plus hashed noise.
GrayImage builtin_map(int w, int h) {
    GrayImage img{w, h, std::vector<std::uint8_t>(std::size_t(w) * h)};
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
            const double v = 128 + 40 * std::sin(x * 0.031 + 0.7 * std::sin(y * 0.017)) + 30 * std::sin(y * 0.047 + x * 0.011) +
                             20 * std::sin((x + y) * 0.13) + double((x * 73856093u ^ y * 19349663u) % 29) - 14;
            img.pixels[std::size_t(y) * w + x] = static_cast<std::uint8_t>(std::clamp(v, 0.0, 255.0));
        }
    return img;
}

// "flat template, flat patch" for a ParticleScore's flags.
std::string flag_names(std::uint32_t flags) {
    std::string out;
    const std::pair<std::uint32_t, const char*> names[] = {
        {kTooFewSamples, "too few samples inside the map"}, {kFlatPatch, "flat map patch"}, {kFlatTemplate, "flat template"}};
    for (const auto& [bit, name] : names)
        if (flags & bit) out += (out.empty() ? "" : ", ") + std::string(name);
    return out;
}

}  // namespace

void add_check_command(CLI::App& app) {
    struct Args {
        int particles = 2000;
        std::string map;
    };
    auto a = std::make_shared<Args>();
    auto* cmd = app.add_subcommand("check", "Quick cross-backend scoring and Sobel run on built-in data, printed as a table");
    cmd->add_option("-n,--particles", a->particles, "Particles to score")->capture_default_str()->transform(whole_in(1, kMaxParticles));
    cmd->add_option("--map", a->map, "Use this map image instead of the built-in one");
    cmd->callback([a] {
        const GrayImage map = a->map.empty() ? builtin_map(1600, 1200) : load_gray(a->map);
        const int tw = 232, th = 174;  // a 640x480 frame at the dissertation's 0.36 map/camera scale
        if (map.width < tw + 2 || map.height < th + 2) throw Error("check: map must be larger than " + std::to_string(tw) + "x" + std::to_string(th));
        const int x0 = map.width / 2 - tw / 2, y0 = map.height / 2 - th / 2;
        GrayImage templ{tw, th, std::vector<std::uint8_t>(std::size_t(tw) * th)};
        for (int v = 0; v < th; ++v) std::copy_n(map.pixels.data() + std::size_t(y0 + v) * map.width + x0, tw, templ.pixels.data() + std::size_t(v) * tw);
        const Pose truth{x0 + (tw - 1) / 2.0f, y0 + (th - 1) / 2.0f, 0, 1};

        std::mt19937 rng(1);
        std::normal_distribution<float> d(0, 60), dyaw(0, 0.2f);
        std::vector<Pose> poses(a->particles);
        for (Pose& p : poses) p = {truth.x + d(rng), truth.y + d(rng), dyaw(rng), 1.0f};
        poses[0] = truth;

        const int sw = 1920, sh = 1080;
        const GrayImage frame = builtin_map(sw, sh);
        std::vector<std::int16_t> gx(std::size_t(sw) * sh), gy(gx.size());

        std::vector<ParticleScore> reference;
        std::printf("map %dx%d, template %dx%d, %d particles (particle 0 at the true pose), Sobel %dx%d\n\n", map.width, map.height, tw, th,
                    a->particles, sw, sh);
        std::printf("%-10s %-34s %12s %14s %10s %12s %14s\n", "backend", "device", "score ms", "particles/s", "best", "max |dNCC|",
                    "sobel ms");
        for (const FamilyStatus& f : default_registry().status(backend_options_from_environment())) {
            if (f.devices.empty()) {
                std::printf("%-10s not available: %s\n", f.family.c_str(), f.why_none.c_str());
                continue;
            }
            for (const DeviceInfo& dev : f.devices) {
                auto backend = default_registry().create(dev.name, backend_options_from_environment());
                const MapHandle h = backend->upload_map(map.view());
                std::vector<ParticleScore> scores(poses.size());
                const ScoringPlan plan = make_scoring_plan(templ.view(), {});
                backend->score(h, plan, poses, scores);  // warm-up: kernel build, buffer allocation
                const auto t0 = std::chrono::steady_clock::now();
                backend->score(h, plan, poses, scores);
                const double ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
                if (reference.empty()) reference = scores;  // cpu-ref comes first
                double worst = 0;
                for (std::size_t i = 0; i < scores.size(); ++i) worst = std::max(worst, double(std::fabs(scores[i].ncc - reference[i].ncc)));
                const auto best = std::max_element(scores.begin(), scores.end(), [](auto& l, auto& r) { return l.ncc < r.ncc; }) - scores.begin();
                backend->sobel(frame.view(), {gx.data(), sw, sh, sw}, {gy.data(), sw, sh, sw});
                const auto s0 = std::chrono::steady_clock::now();
                backend->sobel(frame.view(), {gx.data(), sw, sh, sw}, {gy.data(), sw, sh, sw});
                const double sms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - s0).count();
                std::printf("%-10s %-34.34s %12.2f %14.0f %10s %12.2e %14.2f\n", dev.name.c_str(), dev.device.c_str(), ms,
                            poses.size() / (ms / 1000), best == 0 ? "true pose" : "WRONG", worst, sms);
                // Exact scoring (scoring.hpp): every score, count and flag must equal cpu-ref's.
                const bool same = std::memcmp(scores.data(), reference.data(), scores.size() * sizeof(ParticleScore)) == 0;
                if (best != 0 || !same) throw Error("check: " + dev.name + " disagrees with cpu-ref");
                // A flagged true pose (flat or tiny map) scores 0 like every other flagged particle, so
                // "best" would point at it by accident: nothing was checked, which is a failure.
                const auto flagged = std::count_if(scores.begin(), scores.end(), [](const ParticleScore& s) { return !s.valid(); });
                if (!scores[0].valid())
                    throw Error("check: " + dev.name + ": the true pose is flagged (" + flag_names(scores[0].flags) + "), " +
                                std::to_string(flagged) + " of " + std::to_string(scores.size()) +
                                " particles flagged; the map has no texture to match, so nothing was checked");
                if (flagged > 0)
                    std::fprintf(stderr, "check: warning: %s: %ld of %zu particles flagged (off the map or flat); only their flags were compared\n",
                                 dev.name.c_str(), static_cast<long>(flagged), scores.size());
            }
        }
        std::printf("\nEvery available backend found the true pose and agreed with cpu-ref bit for bit.\n"
                    "Times are single wall-clock runs on this machine; see bench/ for proper measurements.\n");
    });
}

}  // namespace trn::cli
