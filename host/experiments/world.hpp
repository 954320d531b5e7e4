#pragma once
// Maps, frames and noise the studies share: procedural maps (cached per process), the real
// orthophoto from $TRN_SHARED_DATA, rendering a camera frame at a pose and the dissertation's
// camera noise (section 3.2: 5% salt, 5% pepper, Gaussian mean 25 sigma 40).
#include <cstdint>
#include <memory>
#include <string>

#include "trn/detail/splitmix.hpp"
#include "trn/sim/camera.hpp"
#include "trn/sim/map.hpp"
#include "trn/sim/procedural_map.hpp"

namespace trn::experiments {

// The project's SplitMix64 (trn/detail/splitmix.hpp) with the studies' own seeding: the studies
// must not depend on the standard library's distributions.
class Rng {
public:
    explicit Rng(std::uint64_t seed) : state_(seed * splitmix::kGamma + 0x632BE59BD9B4E019ull) {}
    std::uint64_t next() { return splitmix::next64(state_); }
    double uniform() { return splitmix::uniform(state_); }  // [0, 1)
    double normal() { return splitmix::normal(state_); }
    double uniform(double lo, double hi) { return lo + (hi - lo) * uniform(); }

private:
    std::uint64_t state_;
};

std::uint64_t mix_seed(std::uint64_t a, std::uint64_t b);

// A procedural map, generated once per process for the same options.
std::shared_ptr<const sim::Map> procedural_map(sim::TerrainStyle style, std::uint64_t seed, int year, double size_m);

// SHARED_DATA/orthophoto.png ("" when absent or shared_data is "") and the map at 0.5 m per pixel
// (data README). The folder comes from ExperimentOptions::shared_data (the CLI: $TRN_SHARED_DATA).
std::string orthophoto_path(const std::string& shared_data);
inline constexpr double kOrthophotoMetresPerPixel = 0.5;
std::shared_ptr<const sim::Map> orthophoto_map(const std::string& path);
// The orthophoto at `path` aged by `years` with map_ageing (cached).
std::shared_ptr<const sim::Map> aged_orthophoto(const std::string& path, double years, std::uint64_t seed);

// The localization map and the two-years-newer world the frames are rendered from, as the metrics
// and heading studies use them: the orthophoto, or a 1200 m procedural forest (2008 vs 2010).
struct MapPair {
    std::shared_ptr<const sim::Map> map, world;
};
// `orthophoto`: its path, or "" for the procedural forest.
MapPair study_map_pair(const std::string& orthophoto, std::uint64_t seed);

// A level camera frame over `map` at map pixel (x, y), compass heading yaw, with the simulator's
// sensor noise (2% of full scale) seeded by noise_seed.
GrayImage render_at(const sim::Map& map, const sim::Camera& camera, double x, double y, double yaw, double altitude_m,
                    std::uint64_t noise_seed);

// Section 3.2's noise, in place: salt / pepper shares, then additive Gaussian (mean, sigma), clamped.
void add_dissertation_noise(GrayImage& image, std::uint64_t seed, double salt = 0.05, double pepper = 0.05, double mean = 25,
                            double sigma = 40);

}  // namespace trn::experiments
