#pragma once
// Renders camera frames by warping the map: the footprint is low-pass filtered first when the map
// is finer than the camera (no aliasing), sampled bilinearly, and Gaussian sensor noise is added.
#include <cstdint>

#include "trn/sim/camera.hpp"
#include "trn/sim/map.hpp"
#include "trn/export.hpp"

TRN_API_BEGIN
namespace trn::sim {

struct RenderOptions {
    double noise_sigma = 0.02;  // Gaussian noise, share of full scale (0.02 -> 5.1 grey levels)
    bool anti_alias = true;
    std::uint64_t noise_seed = 1;  // same seed -> same noise
};

// A camera frame at `pose`. Parts of the view outside the map are black (0).
GrayImage render_frame(const Map& map, const Camera& camera, const CameraPose& pose, const RenderOptions& options = {});

}  // namespace trn::sim
TRN_API_END
