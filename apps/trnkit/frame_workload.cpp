// The frame of work of `trnkit frames` and `trnkit energy bench` (moved from cmd_frames.cpp so both
// measure the same thing).
#include "frame_workload.hpp"

#include <algorithm>
#include <cmath>
#include <random>
#include <vector>

#include "trn/error.hpp"
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

FrameWorkload make_frame_workload(Backend& backend, const std::string& kernel, const std::string& size, int particles) {
    FrameWorkload work;
    work.meta = {{"backend", backend.info().name}, {"device", backend.info().device}, {"kernel", kernel}};
    for (auto& [k, v] : work.meta)
        for (char& ch : v)
            if (ch == ' ' || ch == '=' || ch == ',') ch = '_';  // the marker header is space-separated key=value
    if (kernel == "sobel") {
        int w = 0, h = 0;
        size_of(size, w, h);
        work.meta["size"] = size;
        // Buffers live as long as the kernel (shared by its copies).
        struct Buffers {
            std::vector<std::uint8_t> img;
            std::vector<std::int16_t> gx, gy;
        };
        auto b = std::make_shared<Buffers>();
        b->img = textured_image(w, h, 1);
        b->gx.resize(b->img.size()), b->gy.resize(b->img.size());
        work.kernel = [&backend, b, w, h] {
            PhaseTimes t;
            backend.sobel({b->img.data(), w, h, w}, {b->gx.data(), w, h, w}, {b->gy.data(), w, h, w}, &t);
            return t;
        };
        return work;
    }
    if (kernel != "ncc") throw Error("--kernel '" + kernel + "': expected sobel or ncc");
    if (particles <= 0) throw Error("--particles must be positive");
    const int mw = 1024, mh = 1024, tw = 64, th = 64;
    work.meta["particles"] = std::to_string(particles);
    const auto map = textured_image(mw, mh, 2);
    std::vector<std::uint8_t> templ(static_cast<std::size_t>(tw) * th);
    for (int y = 0; y < th; ++y)
        for (int x = 0; x < tw; ++x) templ[static_cast<std::size_t>(y) * tw + x] = map[static_cast<std::size_t>(y + 480) * mw + x + 480];
    std::mt19937 rng(3);
    std::uniform_real_distribution<float> pos(200, 800), yaw(-0.3f, 0.3f), scale(0.9f, 1.1f);
    struct State {
        std::vector<Pose> poses;
        std::vector<ParticleScore> scores;
        MapHandle handle;
        ScoringPlan plan;
    };
    auto st = std::make_shared<State>(State{std::vector<Pose>(static_cast<std::size_t>(particles)), {}, backend.upload_map({map.data(), mw, mh, mw}),
                                            make_scoring_plan(TemplateView(GrayView{templ.data(), tw, th, tw}), ScoreOptions{})});
    for (auto& p : st->poses) p = {pos(rng), pos(rng), yaw(rng), scale(rng)};
    st->scores.resize(st->poses.size());
    work.kernel = [&backend, st] {
        PhaseTimes t;
        backend.score(st->handle, st->plan, st->poses, st->scores, &t);
        return t;
    };
    return work;
}

}  // namespace trn::cli
