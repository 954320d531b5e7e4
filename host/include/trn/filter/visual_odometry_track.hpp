#pragma once
// Visual odometry as a track, one frame at a time (issue 43 item 4): the per-frame rules that turn
// VisualOdometry's frame-to-frame motion into metres east / north from the first frame. One home for
// `trnkit localize --odometry visual` (VisualOdometrySource) and the online Localizer
// (LocalizerConfig::visual_odometry), so both compute the same odometry from the same frames.
#include <cmath>
#include <cstddef>

#include "trn/filter/visual_odometry.hpp"
#include "trn/image.hpp"
#include "trn/export.hpp"

TRN_API_BEGIN
namespace trn::filter {

// Each step is scaled by the PREVIOUS frame's metres per frame pixel (its map_px_per_camera_px x the
// map's metres per pixel, i.e. from its altitude) and turned by the previous frame's heading (with
// `own_yaw`, compass-less: by the odometry's own yaw, 0 at the first frame plus every rotation the
// features measured; a phase-correlation step counts as no rotation). A step whose motion is not
// found, or whose previous frame had no scale or heading, is lost (NaN): the track then restarts
// from the current frame, the missed motion is not guessed. A step without a frame keeps the
// reference frame: the next frame is matched across the gap.
class VisualOdometryTrack {
public:
    explicit VisualOdometryTrack(const VisualOdometryOptions& options = {}, bool own_yaw = false);

    struct Step {
        double east_m = NAN, north_m = NAN;  // the track from the first frame (0, 0); NaN: lost / no frame
        double yaw_rad = NAN;                // the heading the track was turned by (own yaw with own_yaw); NaN: lost / no frame
        // "visual:start" (the first frame), "visual:features", "visual:phase", "visual:lost",
        // "visual:no-frame" (static strings).
        const char* source = "visual:no-frame";
    };
    // `frame`: the (levelled) frame, empty: none this step; metres_per_px: its ground metres per
    // pixel (NaN or <= 0: unknown, the next step is lost); heading_rad: the measured heading of its
    // top (ignored with own_yaw).
    Step next(GrayView frame, double metres_per_px, double heading_rad);

    using Counts = VisualOdometryCounts;
    const Counts& counts() const { return counts_; }
    const FrameMotion& last_motion() const { return last_; }
    bool own_yaw() const { return own_yaw_; }

private:
    VisualOdometry vo_;
    FrameMotion last_;
    Counts counts_;
    bool have_reference_ = false, own_yaw_ = false;
    double ref_metres_per_px_ = NAN, ref_heading_ = NAN, yaw_ = 0;
    double east_m_ = 0, north_m_ = 0;
};

}  // namespace trn::filter
TRN_API_END
