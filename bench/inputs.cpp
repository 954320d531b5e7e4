// Benchmark inputs; see inputs.hpp.
#include "inputs.hpp"

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <map>
#include <memory>
#include <random>

#include <opencv2/imgproc.hpp>

#include "../tests/common/shared_data.hpp"
#include "../tests/common/test_images.hpp"
#include "trn/error.hpp"
#include "trn/io/image_io.hpp"

namespace trn::bench {

std::filesystem::path shared_data_path(const std::filesystem::path& relative) {
    const std::filesystem::path dir = trn::test::shared_data_dir();
    return dir.empty() ? dir : dir / relative;
}

namespace {

// The tests' texture (blurred noise with hard edges, like aerial imagery), with more edges.
cv::Mat synthetic_map(int w, int h) { return test::textured_mat(w, h, 20240601, 40, 4); }

MapInput load_map() {
    if (const std::filesystem::path path = shared_data_path("orthophoto.png"); !path.empty()) {
        if (std::filesystem::exists(path)) {
            const GrayImage img = load_gray(path.string());
            cv::Mat m(img.height, img.width, CV_8UC1, const_cast<std::uint8_t*>(img.pixels.data()));
            return {m.clone(), "orthophoto.png " + std::to_string(img.width) + "x" + std::to_string(img.height)};
        }
    }
    return {synthetic_map(2048, 2048), "synthetic 2048x2048"};
}

void fill_random(std::uint8_t* p, std::size_t n, std::uint64_t seed) {
    std::uint64_t s = seed | 1;
    for (std::size_t i = 0; i < n; ++i) {
        s ^= s << 13, s ^= s >> 7, s ^= s << 17;  // xorshift64: fast enough for a GiB
        p[i] = static_cast<std::uint8_t>(s >> 32);
    }
}

SobelFrames make_frames(const FrameSize& size, int count) {
    const std::size_t px = std::size_t(size.width) * size.height;
    SobelFrames f{size, count, std::vector<std::uint8_t>(px * count), std::vector<std::int16_t>(px * count),
                  std::vector<std::int16_t>(px * count)};
    fill_random(f.src.data(), f.src.size(), 0x5eed + size.width);
    return f;
}

}  // namespace

const MapInput& bench_map() {
    static const MapInput map = load_map();
    return map;
}

cv::Mat template_from_map(const FrameSize& size) {
    const cv::Mat& m = bench_map().pixels;
    if (size.width > m.cols || size.height > m.rows)
        throw Error("bench: template " + size.text() + " is larger than the map " + bench_map().source);
    const cv::Rect roi((m.cols - size.width) / 2, (m.rows - size.height) / 2, size.width, size.height);
    return m(roi).clone();
}

std::vector<Pose> poses_around_centre(int count) {
    const cv::Mat& m = bench_map().pixels;
    const float cx = float(m.cols - 1) / 2, cy = float(m.rows - 1) / 2;
    std::mt19937 rng(12345);
    std::uniform_real_distribution<float> shift(-24.0f, 24.0f), yaw(-0.25f, 0.25f), scale(0.95f, 1.05f);
    std::vector<Pose> poses(count);
    for (Pose& p : poses) p = {cx + shift(rng), cy + shift(rng), yaw(rng), scale(rng)};
    return poses;
}

std::vector<Pose> poses_over_the_edge(int count, const FrameSize& templ) {
    const cv::Mat& m = bench_map().pixels;
    const float w = float(m.cols - 1), h = float(m.rows - 1), reach = 0.5f * float(std::min(templ.width, templ.height));
    std::mt19937 rng(54321);
    std::uniform_real_distribution<float> along(0.0f, 1.0f), across(-reach, reach), yaw(-0.25f, 0.25f), scale(0.95f, 1.05f);
    std::vector<Pose> poses(count);
    for (int i = 0; i < count; ++i) {
        const float a = along(rng), b = across(rng);
        const float x[] = {a * w, a * w, b, w + b}, y[] = {b, h + b, a * h, a * h};  // top, bottom, left, right
        poses[i] = {x[i % 4], y[i % 4], yaw(rng), scale(rng)};
    }
    return poses;
}

const MaskedMapInput* masked_map(const std::string& name, const FrameSize& templ) {
    // Each flight: its map, its first frame, and the ground a frame spans at about 60 m above
    // ground (2 * 60 m * tan(hfov / 2)) over the map's metres per pixel (the flights' READMEs).
    struct Flight {
        const char *name, *map, *frame;
        double ground_m, m_per_px;
    };
    static const Flight flights[] = {{"realflight2", "realflight2/orthomosaic.png", "realflight2/frames/frame_00000.png", 82.5, 0.27},
                                     {"realflight3", "realflight3/air/map.png", "realflight3/frames/frame_00000.png", 86.5, 0.4551}};
    static std::map<std::string, std::unique_ptr<MaskedMapInput>> loaded;
    const std::string key = name + "/" + templ.text();
    if (auto it = loaded.find(key); it != loaded.end()) return it->second.get();
    std::unique_ptr<MaskedMapInput>& slot = loaded[key];
    for (const Flight& f : flights) {
        const std::filesystem::path map_path = shared_data_path(f.map), frame_path = shared_data_path(f.frame);
        if (name != f.name || map_path.empty()) continue;
        if (!std::filesystem::exists(map_path) || !std::filesystem::exists(frame_path)) break;
        const GrayImage grey = load_gray(map_path.string()), valid = load_validity(map_path.string()), frame = load_gray(frame_path.string());
        if (valid.width != grey.width) throw Error("bench: " + map_path.string() + " has no alpha (no-data)");
        auto in = std::make_unique<MaskedMapInput>();
        in->name = f.name;
        in->pixels = cv::Mat(grey.height, grey.width, CV_8UC1, const_cast<std::uint8_t*>(grey.pixels.data())).clone();
        in->valid = cv::Mat(valid.height, valid.width, CV_8UC1, const_cast<std::uint8_t*>(valid.pixels.data())).clone();
        const cv::Mat cam(frame.height, frame.width, CV_8UC1, const_cast<std::uint8_t*>(frame.pixels.data()));
        cv::resize(cam, in->templ, cv::Size(templ.width, templ.height), 0, 0, cv::INTER_AREA);
        in->scale = float(f.ground_m / f.m_per_px / templ.width);
        in->valid_share = double(cv::countNonZero(in->valid)) / double(in->valid.total());
        in->source = std::string(f.map) + " " + std::to_string(grey.width) + "x" + std::to_string(grey.height) + ", " +
                     std::to_string(int(std::lround(100 * in->valid_share))) + " % valid";
        slot = std::move(in);
        break;
    }
    return slot.get();
}

std::vector<Pose> poses_on_valid(const MaskedMapInput& map, int count) {
    std::mt19937 rng(24680);
    std::uniform_int_distribution<int> ux(0, map.valid.cols - 1), uy(0, map.valid.rows - 1);
    std::uniform_real_distribution<float> sub(0.0f, 1.0f), yaw(-3.14159f, 3.14159f), scale(0.95f, 1.05f);
    std::vector<Pose> poses;
    while (int(poses.size()) < count) {
        const int x = ux(rng), y = uy(rng);
        if (!map.valid.at<std::uint8_t>(y, x)) continue;
        poses.push_back({float(x) + sub(rng), float(y) + sub(rng), yaw(rng), map.scale * scale(rng)});
    }
    return poses;
}

SobelFrames frame_set(const FrameSize& size, int count) { return make_frames(size, count); }

SobelFrames cold_frames(const FrameSize& size, std::size_t bytes) {
    const double per_frame = kSobelBytesPerPixel * size.width * size.height;
    const int count = std::max(2, static_cast<int>(std::ceil(double(bytes) / per_frame)));
    return make_frames(size, count);
}

}  // namespace trn::bench
