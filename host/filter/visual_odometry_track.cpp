#include "trn/filter/visual_odometry_track.hpp"

#include "trn/detail/angles.hpp"

namespace trn::filter {

VisualOdometryTrack::VisualOdometryTrack(const VisualOdometryOptions& options, bool own_yaw) : vo_(options), own_yaw_(own_yaw) {}

VisualOdometryTrack::Step VisualOdometryTrack::next(GrayView frame, double metres_per_px, double heading_rad) {
    Step s;
    if (frame.empty()) {  // keep the reference: the next frame is matched across the gap
        ++counts_.no_frame;
        return s;
    }
    last_ = vo_.track(frame);
    if (!have_reference_) {
        have_reference_ = true;
        s.east_m = east_m_, s.north_m = north_m_;
        s.yaw_rad = own_yaw_ ? yaw_ : heading_rad;
        s.source = "visual:start";
    } else if (last_.ok() && std::isfinite(ref_metres_per_px_) && std::isfinite(ref_heading_)) {
        const GroundStep g = ground_displacement(last_.dx_px, last_.dy_px, ref_metres_per_px_, ref_heading_);
        east_m_ += g.east_m, north_m_ += g.north_m;
        s.east_m = east_m_, s.north_m = north_m_;
        if (own_yaw_ && std::isfinite(last_.rotation_rad)) yaw_ = wrap_angle(yaw_ + last_.rotation_rad);
        s.yaw_rad = own_yaw_ ? yaw_ : heading_rad;
        const bool features = last_.method == MotionMethod::Features;
        ++(features ? counts_.features : counts_.phase);
        s.source = features ? "visual:features" : "visual:phase";
    } else {
        ++counts_.lost;
        s.source = "visual:lost";
    }
    ref_metres_per_px_ = metres_per_px > 0 ? metres_per_px : NAN;
    ref_heading_ = own_yaw_ ? yaw_ : heading_rad;
    return s;
}

}  // namespace trn::filter
