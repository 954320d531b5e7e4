#pragma once
// Benchmark inputs, built once and shared: the map (the real orthophoto when $TRN_SHARED_DATA has
// it, else a textured synthetic map), templates cut from it, particle poses around the true pose,
// and Sobel frames (one hot frame per size, or a rotating working set larger than the cache).
#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

#include <opencv2/core.hpp>

#include "sweep.hpp"
#include "trn/scoring.hpp"

namespace trn::bench {

// `relative` under $TRN_SHARED_DATA (the project's real data), or an empty path when the variable
// is unset or empty (tests/common/shared_data.hpp reads the variable for tests and benchmarks).
std::filesystem::path shared_data_path(const std::filesystem::path& relative);

struct MapInput {
    cv::Mat pixels;      // CV_8UC1, continuous
    std::string source;  // "orthophoto.png" or "synthetic 2048x2048"
};
const MapInput& bench_map();

// A template of the given size cut from the middle of the map (continuous CV_8UC1).
cv::Mat template_from_map(const FrameSize& size);

// `count` poses spread around the template's true pose (+-24 px, +-0.25 rad, scale 0.95..1.05),
// the way a particle cloud sits around the vehicle; fixed seed, so every backend gets the same.
std::vector<Pose> poses_around_centre(int count);
// `count` poses whose patches of `templ` cross the map's edge: centres within half the template
// of one of the four edges (in turn), yaw and scale as poses_around_centre; fixed seed. A particle cloud near
// the map's border, or spread wide at the start, has many of these.
std::vector<Pose> poses_over_the_edge(int count, const FrameSize& templ);

// A real orthomosaic with no-data (its alpha) from $TRN_SHARED_DATA, for the masked-map cases:
// the grey map, its validity (255 valid, 0 no-data), the first real frame of that flight
// area-downscaled to the filter's template, and the flight's map pixels per template pixel.
struct MaskedMapInput {
    std::string name;    // "realflight2", "realflight3"
    cv::Mat pixels;      // CV_8UC1, continuous
    cv::Mat valid;       // CV_8UC1, continuous
    cv::Mat templ;       // CV_8UC1, continuous, the template size asked for
    float scale = 1.0f;  // the flight's scale (map px per template px at about 60 m above ground)
    double valid_share = 0;  // share of valid pixels
    std::string source;  // "realflight2/orthomosaic.png 976x861, 54 % valid"
};
// nullptr when $TRN_SHARED_DATA does not hold that flight.
const MaskedMapInput* masked_map(const std::string& name, const FrameSize& templ);
// `count` poses of a cloud spread over the map's imagery: centres on valid pixels (uniform),
// any yaw, scale within 5 % of the flight's; fixed seed. Patches near the no-data's edge cross it.
std::vector<Pose> poses_on_valid(const MaskedMapInput& map, int count);

// Frames for Sobel: `count` source images (random bytes) and room for their gradients, laid out
// one after another so consecutive iterations touch different memory.
struct SobelFrames {
    FrameSize size;
    int count = 0;
    std::vector<std::uint8_t> src;
    std::vector<std::int16_t> gx, gy;
    int cursor = 0;  // next frame to use: rotation continues across benchmark calls, so no frame is reused early
    int next() { const int k = cursor; cursor = (cursor + 1) % count; return k; }
    const std::uint8_t* src_at(int i) const { return src.data() + std::size_t(i) * size.width * size.height; }
    std::int16_t* gx_at(int i) { return gx.data() + std::size_t(i) * size.width * size.height; }
    std::int16_t* gy_at(int i) { return gy.data() + std::size_t(i) * size.width * size.height; }
};
// `count` frames (count 1: hot, the frame stays in cache between iterations).
SobelFrames frame_set(const FrameSize& size, int count);
// As many frames as fit in `bytes` of traffic (1 B in + 4 B out per pixel), at least 2.
SobelFrames cold_frames(const FrameSize& size, std::size_t bytes);

// Compulsory Sobel traffic per pixel: one byte in, two int16 out.
inline constexpr double kSobelBytesPerPixel = 5.0;

}  // namespace trn::bench
