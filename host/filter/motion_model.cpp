#include "trn/filter/motion_model.hpp"

#include <cmath>
#include <string>

#include "trn/error.hpp"
#include "trn/detail/angles.hpp"

namespace trn::filter {
void MotionModel::validate() const {
    auto in_range = [](double v, double lo, double hi, const char* name) {
        if (!(v >= lo && v <= hi))
            throw Error(std::string("motion model: ") + name + " " + std::to_string(v) + " must be finite and in [" +
                        std::to_string(lo) + ", " + std::to_string(hi) + "]");
    };
    in_range(alpha1, 0, 1, "alpha1");
    in_range(alpha2, 0, 1, "alpha2");
    in_range(alpha3, 0, 5, "alpha3");
    in_range(eps_tran_m, 0, 1000, "eps_tran_m");
    in_range(eps_tran_m_per_s, 0, 100, "eps_tran_m_per_s");
    in_range(eps_rot_deg, 0, 180, "eps_rot_deg");
    in_range(yaw_sd_deg, 0, 180, "yaw_sd_deg");
    in_range(yaw_turn_sd, 0, 5, "yaw_turn_sd");
    in_range(yaw_unknown_sd_deg, 0, 180, "yaw_unknown_sd_deg");
    if (equations != MotionEquations::Ours && equations != MotionEquations::Dissertation)
        throw Error("motion model: equations must be Ours or Dissertation");
    if (equations == MotionEquations::Dissertation && along_heading)
        throw Error("motion model: along_heading is an option of our equations; the dissertation's move along the heading anyway");
}

StepMotion make_step_motion(double east_m, double north_m, double heading_rad, double frame_heading_rad, double turn_rad,
                            double mpp) {
    StepMotion m;
    m.east_px = east_m / mpp, m.north_px = north_m / mpp;
    m.distance_px = std::hypot(m.east_px, m.north_px);
    m.have_heading = std::isfinite(heading_rad);
    m.heading_rad = m.have_heading ? heading_rad : 0;
    m.turn_rad = std::isfinite(turn_rad) ? std::abs(turn_rad) : 0;
    m.heading_change_rad = std::isfinite(turn_rad) ? turn_rad : 0;
    if (std::isfinite(frame_heading_rad) && m.distance_px > 0) {
        // Forward / right of the heading (compass: forward = (sin, cos) in east/north).
        const double s = std::sin(frame_heading_rad), c = std::cos(frame_heading_rad);
        const double forward = m.east_px * s + m.north_px * c, right = m.east_px * c - m.north_px * s;
        m.course_offset_rad = std::atan2(right, forward);
    }
    return m;
}

StepMotion make_yaw_state_motion(double right_m, double forward_m, double rotation_rad, double mpp) {
    // The increment against heading 0: north = forward, east = right, so delta_c = atan2(right, forward).
    StepMotion m = make_step_motion(right_m, forward_m, NAN, 0.0, rotation_rad, mpp);
    m.yaw_state = true;
    m.rotation_rad = std::isfinite(rotation_rad) ? wrap_angle(rotation_rad) : NAN;
    return m;
}

namespace {
// The translation of one step from a particle's course heading (shared by both modes): the
// odometry's distance and course with along/across-track noise.
void translate(const MotionModel& model, const StepMotion& m, double mpp, const std::array<double, 5>& z, double heading, double& x,
               double& y) {
    const double d = m.distance_px * (1 + model.alpha1 * m.noise_gain * z[1]);
    const double offset = model.along_heading ? 0.0 : m.course_offset_rad;
    const double course = heading + offset + ((model.alpha2 * m.noise_gain) + model.alpha3 * m.turn_rad) * z[2];
    // hypot(a, 0) == a exactly: without frame times the draws and sums are those of the step model.
    const double pos_sd = std::hypot(model.eps_tran_m / mpp, m.time_sd_px) + m.diffusion_px;
    x += d * std::sin(course) + pos_sd * z[3];
    y -= d * std::cos(course) + pos_sd * z[4];
}
}  // namespace

namespace {
// Eqs. 2.7-2.11 as printed (motion_model.hpp): z[0] the rotation's draw, z[1] the translation's.
void propagate_as_printed(const MotionModel& model, const StepMotion& m, double mpp, const std::array<double, 5>& z, double& x,
                          double& y, double& yaw) {
    constexpr double kSampleNormalSd = 1.0 / 3.0;  // the paper: sample_normal(eps) = eps * N(0, 1/3)
    const double rotation = m.yaw_state ? (std::isfinite(m.rotation_rad) ? m.rotation_rad : 0.0) : m.heading_change_rad;
    const double d_rot = rotation + model.eps_rot_deg * kDeg * kSampleNormalSd * z[0];
    const double d_tran = m.distance_px + model.eps_tran_m / mpp * m.noise_gain * kSampleNormalSd * z[1];
    yaw = wrap_angle(yaw + model.alpha3 * d_rot);
    x += model.alpha1 * d_tran * std::sin(yaw);
    y -= model.alpha2 * d_tran * std::cos(yaw);
}
}  // namespace

void propagate_particle(const MotionModel& model, const StepMotion& m, double mpp, const std::array<double, 5>& z, double& x,
                        double& y, double& yaw) {
    if (model.equations == MotionEquations::Dissertation) return propagate_as_printed(model, m, mpp, z, x, y, yaw);
    if (m.yaw_state) {  // moved along the yaw it had, then turned by the odometry's rotation
        translate(model, m, mpp, z, yaw, x, y);
        const bool known = std::isfinite(m.rotation_rad);
        const double sd = known ? model.yaw_sd_deg * kDeg + model.yaw_turn_sd * std::abs(m.rotation_rad) : model.yaw_unknown_sd_deg * kDeg;
        yaw = wrap_angle(yaw + (known ? m.rotation_rad : 0.0) + sd * z[0]);
        return;
    }
    yaw = wrap_angle((m.have_heading ? m.heading_rad : yaw) + model.eps_rot_deg * kDeg * z[0]);
    translate(model, m, mpp, z, yaw, x, y);
}

}  // namespace trn::filter
