#pragma once
// Image-based visual odometry (issue 17 item 4): the camera's motion between consecutive downward
// frames, from ORB features and a RANSAC similarity (rotation, scale, shift), with phase
// correlation as the fallback when the features give no consensus. The shift of the frame centre
// becomes metres east/north with the measured altitude (metres per frame pixel = altitude *
// 2 tan(hfov/2) / width, i.e. the sample's map_px_per_camera_px x the map's metres per pixel) and
// the measured heading of the frame top. Frame to frame only: errors add up like any odometry's.
#include <cmath>
#include <cstddef>
#include <memory>
#include <string>

#include "trn/filter/flight_source.hpp"
#include "trn/image.hpp"
#include "trn/export.hpp"

TRN_API_BEGIN
namespace trn::filter {

struct VisualOdometryOptions {
    int max_features = 1500;           // ORB keypoints per frame
    int max_width = 640;               // wider frames are downscaled first (speed; shifts stay sub-pixel)
    double ransac_threshold_px = 2.0;  // inlier distance, pixels of the (downscaled) working frame
    int ransac_iterations = 2000;
    double ransac_confidence = 0.99;
    // Fewer RANSAC inliers than this and the feature motion is not trusted. A similarity has 4
    // degrees of freedom (2 matches fix it), so a few wrong matches always agree by chance: between
    // frames with no common ground we measured 4-6 (8 real pairs, rendered pairs: 4); 12 is twice
    // that. Overlapping frames give 21-327 (real) and 600+ (rendered). (docs/RESULTS.md "Visual odometry")
    int min_inliers = 12;
    bool phase_correlation = true;     // fallback when the features fail (pure shift; same-size frames)
    // Phase-correlation peaks below this are not trusted: frames with no common ground peak at
    // up to 0.022 (measured, 8 real pairs), overlapping rendered frames at 0.21-1.17.
    double min_phase_response = 0.1;

    void validate() const;  // throws trn::Error naming the field
};

enum class MotionMethod { None, Features, PhaseCorrelation };
const char* to_string(MotionMethod m);  // "none", "features", "phase"

// Where the current frame's centre lies relative to the previous frame's centre, in pixels of the
// previous frame (its own size): the camera's ground displacement as the previous frame saw it.
struct FrameMotion {
    MotionMethod method = MotionMethod::None;
    double dx_px = NAN, dy_px = NAN;
    double rotation_rad = NAN;  // current frame relative to the previous (features only)
    double scale = NAN;         // previous px per current px (features only; altitude change)
    int inliers = 0;            // RANSAC inliers of the feature fit (also when it was refused)
    double response = 0;        // phase-correlation peak (when tried)
    std::string failure;        // why method is None
    bool ok() const { return method != MotionMethod::None; }
};

class VisualOdometryTrack;  // visual_odometry_track.hpp

// Steps of a visual-odometry track by how they went (VisualOdometryTrack, VisualOdometrySource).
struct VisualOdometryCounts {
    std::size_t features = 0, phase = 0, lost = 0, no_frame = 0;
};

// Frame-to-frame tracker: each frame's features are computed once and kept for the next call.
class VisualOdometry {
public:
    explicit VisualOdometry(const VisualOdometryOptions& options = {});
    ~VisualOdometry();
    VisualOdometry(const VisualOdometry&) = delete;
    VisualOdometry& operator=(const VisualOdometry&) = delete;

    // Motion from the frame of the previous call to `frame` (method None, failure "first frame",
    // on the first call), which then becomes the reference, whether the motion was found or not.
    FrameMotion track(GrayView frame);
    void reset();  // forget the reference frame

private:
    struct Reference;
    VisualOdometryOptions options_;
    std::unique_ptr<Reference> reference_;
};

// The motion of `current` against `previous` (both 8-bit grey, at least 16 x 16).
FrameMotion estimate_frame_motion(GrayView previous, GrayView current, const VisualOdometryOptions& options = {});

// A displacement in frame pixels (dx right, dy down) as metres east / north: the frame top points
// at heading_rad (clockwise from north), one pixel is metres_per_px on the ground (camera.hpp).
struct GroundStep {
    double east_m = 0, north_m = 0;
};
GroundStep ground_displacement(double dx_px, double dy_px, double metres_per_px, double heading_rad);

// A FlightSource whose odometry is the visual odometry of its own frames: wraps `inner` (kept
// alive by the caller) and replaces each sample's odometry_east_m / north_m with the accumulated
// track from the first frame (0, 0), by VisualOdometryTrack's rules (visual_odometry_track.hpp; the
// online Localizer's visual_odometry follows the same): each step scaled by the previous frame's
// measured altitude (its map_px_per_camera_px x map_metres_per_pixel) and turned by the previous
// frame's measured heading. A step whose motion is not found, or a sample without a frame, is NaN
// (the filter counts it as odometry lost); the track then restarts from the current frame, the
// missed motion is not guessed. FlightSample::odometry_source says per sample: "visual:features",
// "visual:phase", "visual:lost" or "visual:no-frame" ("visual:start" for the first frame).
// FlightSample::odometry_yaw_rad is the heading the track was turned by (NaN while lost).
// With `own_yaw` (compass-less localization) the measured headings are not used: the track is
// turned by the odometry's own yaw instead, 0 at the first frame plus every rotation the features
// measured (FrameMotion::rotation_rad; a phase-correlation step counts as no rotation), which is
// then the sample's odometry_yaw_rad. Its increments are the frames' own motion exactly: the
// shift in the previous frame's axes and the rotation between the two frames.
class VisualOdometrySource : public FlightSource {
public:
    VisualOdometrySource(FlightSource& inner, double map_metres_per_pixel, const VisualOdometryOptions& options = {},
                         bool own_yaw = false);
    ~VisualOdometrySource() override;
    bool next(FlightSample& sample) override;
    std::size_t frames_hint() const override { return inner_.frames_hint(); }

    using Counts = VisualOdometryCounts;
    const Counts& counts() const;
    const FrameMotion& last_motion() const;

private:
    FlightSource& inner_;
    double mpp_;
    std::unique_ptr<VisualOdometryTrack> track_;
};

}  // namespace trn::filter
TRN_API_END
