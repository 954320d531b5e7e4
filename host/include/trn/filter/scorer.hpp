#pragma once
// How the particle filter measures particles: one batched call per camera frame. The filter only
// sees this interface, so it can be embedded with any scorer; BackendScorer is the real one that
// hands every particle to a trn::Backend in one Backend::score call.
#include <memory>
#include <span>
#include <utility>

#include "trn/backend.hpp"
#include "trn/io/image_io.hpp"
#include "trn/export.hpp"

TRN_API_BEGIN
namespace trn::filter {

class ParticleScorer {
public:
    virtual ~ParticleScorer() = default;
    // Scores `poses` (map-pixel x, y, yaw; `scale` is ignored and derived here) against the camera
    // frame, whose pixels each cover `map_px_per_camera_px` map pixels. out.size() >= poses.size().
    virtual void score(GrayView camera_frame, double map_px_per_camera_px, std::span<const Pose> poses,
                       std::span<ParticleScore> out, PhaseTimes* times) = 0;
    // The map's size in pixels, {0, 0} when the scorer does not know it (the lock monitor then
    // places its probes without regard to the map's edges).
    virtual std::pair<int, int> map_size() const { return {0, 0}; }
};

struct BackendScorerOptions {
    int template_width = 160;  // the camera frame is area-downscaled to this width first (0: keep)
    Sampling sampling;         // dense, or Sampling::random(fraction, seed)
    double min_valid_fraction = 0.9;  // the Localizer sets it from its filter's update.min_valid_fraction
};

// Uploads the map once; per frame downsizes the camera frame, builds the plan and scores all
// particles in one Backend::score call. The backend must outlive the scorer.
class BackendScorer : public ParticleScorer {
public:
    // `valid`: the map's no-data (Backend::upload_map); empty: every pixel valid.
    BackendScorer(Backend& backend, GrayView map, const BackendScorerOptions& options = {}, GrayView valid = {});
    void score(GrayView camera_frame, double map_px_per_camera_px, std::span<const Pose> poses,
               std::span<ParticleScore> out, PhaseTimes* times) override;
    const BackendScorerOptions& options() const { return options_; }
    std::pair<int, int> map_size() const override { return {map_width_, map_height_}; }

private:
    Backend& backend_;
    int map_width_, map_height_;
    MapHandle map_;
    BackendScorerOptions options_;
    std::vector<Pose> scaled_;
    GrayImage small_;
};

// Area-averaging downscale to `width` (height keeps the aspect ratio); a copy when width >= the
// frame's. Returns the scale factor (source pixels per output pixel) through `factor`.
GrayImage downscale_frame(GrayView frame, int width, double& factor);

}  // namespace trn::filter
TRN_API_END
