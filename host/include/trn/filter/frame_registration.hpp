#pragma once
// Finding the poses of consecutive real camera frames on an orthophoto (`trnkit register`), and
// checking a set of poses: each must be the single best NCC within a window around it.
//
// Method: frame-to-frame motion (ORB + RANSAC, same season, large overlap) chained to frame 0; a
// coarse global search of the whole chained strip over yaw and scale (a mosaic of all frames
// matched against the map, so a long straight road cannot fool it); a joint refinement of the
// anchor pose and scale with trnkit's own scorer (mean NCC over all frames); then, frame by frame,
// a local NCC refinement around the previous frame's pose moved by the frame motion.
#include <optional>
#include <string>
#include <vector>

#include "trn/backend.hpp"
#include "trn/io/image_io.hpp"
#include "trn/scoring.hpp"
#include "trn/export.hpp"

TRN_API_BEGIN
namespace trn::reg {

// p' = [a -b; b a] p + (tx, ty): rotation atan2(b, a), scale hypot(a, b), in image pixels.
struct Similarity {
    double a = 1, b = 0, tx = 0, ty = 0;
    double angle() const;
    double scale() const;
};
Similarity compose(const Similarity& outer, const Similarity& inner);  // outer(inner(p))

// The camera looks slightly forward, so a similarity fitted to consecutive frames reads the move
// into the far (smaller) part of the view as a ~3.5 % zoom per frame, which chained over 15 frames
// is a 40 % scale error that the map refutes. The frames come already scaled to about one ground
// resolution (their sizes differ), so the chain keeps the fitted rotation and the motion of the
// frame centre and drops the scale: next_to_this is rigid about frame k+1's centre.
struct RelativeMotion {
    Similarity next_to_this;  // frame k+1 pixels -> frame k pixels (rigid)
    double fitted_scale = 1;  // the similarity fit's scale, reported only
    int inliers = 0;
};

// Motion between consecutive frames; throws trn::Error naming the pair when it cannot be found.
std::vector<RelativeMotion> relative_motions(const std::vector<GrayImage>& frames, const std::vector<std::string>& names);
// Frame k pixels -> frame 0 pixels, k = 0..n-1.
std::vector<Similarity> chain(const std::vector<RelativeMotion>& motions);

// Pose of frame k given frame 0's pose and the chain; frames may differ in size (the centres differ).
Pose chained_pose(const Pose& anchor, const Similarity& to_frame0, const GrayImage& frame0, const GrayImage& frame_k);

struct FramePose {
    Pose pose;
    double ncc = 0;
    double dx = 0, dy = 0;              // refined minus predicted (previous pose + frame motion), map px
    double chain_dx = 0, chain_dy = 0;  // refined minus the joint chain (anchor + chained motion), map px
};

struct RegisterOptions {
    double min_scale = 0.30, max_scale = 1.50;  // map px per frame px searched globally
    double yaw_step_deg = 3;                     // global yaw step
    double refine_radius_px = 16;                // per-frame refinement window around the prediction (map px)
    std::optional<Pose> anchor_hint;             // frame 0's approximate pose: skips the global search
};

struct Registration {
    std::vector<RelativeMotion> motions;
    std::vector<Similarity> chain;
    Pose anchor;              // frame 0 after the joint refinement
    double joint_ncc = 0;     // mean NCC of the chained poses
    std::vector<FramePose> frames;
};

// `valid`: the map's no-data (Backend::upload_map), honoured by every score; the coarse global
// search sees it filled with the valid pixels' mean grey.
Registration register_frames(Backend& backend, const GrayImage& map, const std::vector<GrayImage>& frames,
                             const std::vector<std::string>& names, const RegisterOptions& options, GrayView valid = {});

// NCC of `pose` (dense) and, on a (2r+1)^2 grid (step px) around it at the same yaw and scale
// (half-resolution template, sparse samples), the best pose and the runner-up: the best other
// local maximum of the grid.
struct Uniqueness {
    double ncc_at_pose = 0;
    double best_ncc = 0, best_dist = 0;            // best of the grid, its distance from pose
    Pose best;
    double runner_up_ncc = 0, runner_up_dist = 0;  // distance from pose
};
// Within this distance of the best grid point a local maximum is the same peak (road ridges),
// and the best grid point may lie this far from a dense optimum: the poses' uncertainty (~4 m).
inline constexpr double kShoulderPx = 8;
Uniqueness check_unique(Backend& backend, const MapHandle& map, const GrayImage& frame, const Pose& pose, double radius,
                        double step);

// A frame downscaled so one template pixel is about one map pixel at `scale`, with the pose
// scale that goes with it (scores of the same ground, ~6x fewer samples).
struct ScaledTemplate {
    GrayImage image;
    double factor = 1;  // frame pixels per template pixel
};
ScaledTemplate template_for_scale(const GrayImage& frame, double scale);

// The poses file: header "frame,x,y,yaw,scale,ncc" then one row per frame (frame = file name);
// further columns are ignored. Errors name the file and line.
struct PoseRow {
    std::string frame;
    Pose pose;
    double ncc = 0;
};
std::vector<PoseRow> read_pose_rows(const std::string& path);

}  // namespace trn::reg
TRN_API_END
