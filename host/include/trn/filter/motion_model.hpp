#pragma once
// The particle motion model: the dissertation's eqs. 2.7-2.11 generalised from "the odometry's
// distance along the heading" to "the odometry's displacement vector".
//
// Reading of the equations (docs/RESULTS.md, "Motion model"): per step the odometry gives an
// increment (east, north) and the magnetometer/IMU a heading psi of the camera. The increment is
// expressed in the frame of psi: forward f and sideways r, so delta_tran = |(f, r)| and the
// course offset delta_c = atan2(r, f) (the crab angle: wind, mount yaw; 0 when the camera points
// along the track). Each particle then moves
//     theta' = psi + N(0, eps_rot)                                   (eqs. 2.9, 2.11)
//     d      = delta_tran * (1 + alpha1 * N(0,1))                     (eq. 2.10, along track)
//     c      = theta' + delta_c + (alpha2 + alpha3 * |turn|) * N(0,1)  (course, across track)
//     x'     = x + d sin(c) + N(0, eps_tran),  y' = y - d cos(c) + N(0, eps_tran)   (eqs. 2.7, 2.8)
// (compass convention: x east, y south). A particle at the true heading with no noise follows
// the odometry's track exactly, crab or not. `along_heading` drops the crab offset (delta_c = 0:
// the distance is moved along the measured heading, the odometry's direction is lost) and keeps
// everything else of this model (the heading reset to the magnetometer, the alpha roles above); it
// is not the dissertation's equations, which are `equations = MotionEquations::Dissertation`.
//
// MotionEquations::Dissertation: eqs. 2.7-2.11 as printed (dissertation 2.3.3; the paper's eqs. 6-8
// and its sample_normal), in the compass convention (the text's x = cos, y = sin pair is the
// mathematical one; here x east = sin, y south = -cos of the compass heading):
//     d_tran = delta_tran + sample_normal(eps_tran)                         (eq. 2.10)
//     d_rot  = delta_rot  + sample_normal(eps_rot)                          (eq. 2.11)
//     theta' = theta + alpha3 * d_rot                                       (eq. 2.9)
//     x'     = x + alpha1 * d_tran * sin(theta'),  y' = y - alpha2 * d_tran * cos(theta')   (eqs. 2.7, 2.8)
// with sample_normal(eps) = eps * N(0, 1/3) (the paper), read as eps times a normal draw of sd 1/3
// (eps is then a 3-sigma bound; the other reading, variance 1/3, would be sd 0.577). delta_tran =
// the odometry's distance this step, delta_rot = the heading's change since the previous step (the
// magnetometer's; without a compass the odometry's rotation, 0 when unknown). The particle keeps its
// own heading theta (no reset to the magnetometer), moves along it (no crab offset) and the alphas
// scale the motion (1 = as measured). eps_tran_m / eps_rot_deg are these eps; noise_gain (lost
// odometry, not in the text) scales eps_tran. alpha2/alpha3 carry the text's roles, not ours.
//
// Without a compass (StepMotion::yaw_state, FilterConfig::heading = HeadingMode::None) yaw is part
// of each particle's state. The increment is then expressed in the previous frame's own axes (as if
// its top pointed north: north = forward, towards the frame top; east = to its right), and the
// odometry also gives the rotation of the frame since the previous step, dpsi (NaN: unknown):
//     c      = theta + delta_c + (alpha2 + alpha3 * |dpsi|) * N(0,1)  (theta: the particle's yaw before the step)
//     x', y' as above
//     theta' = theta + dpsi + (yaw_sd_deg + yaw_turn_sd * |dpsi|) * N(0,1)
// and theta' = theta + yaw_unknown_sd_deg * N(0,1) when dpsi is unknown (odometry lost).
#include <array>
#include <cmath>
#include "trn/export.hpp"

TRN_API_BEGIN
namespace trn::filter {

enum class MotionEquations {
    Ours,          // the displacement-vector model above (the default)
    Dissertation,  // eqs. 2.7-2.11 as printed (see above)
};

struct MotionModel {
    MotionEquations equations = MotionEquations::Ours;
    bool along_heading = false;  // Ours only: drop the crab offset (not the dissertation's equations)
    double alpha1 = 0.05;      // along-track sd per metre moved (the odometry's scale error)
    double alpha2 = 0.03;      // course sd, radians (= across-track sd per metre moved)
    double alpha3 = 0.2;       // extra course sd per radian the heading turned this step (odometry in turns)
    double eps_tran_m = 1.0;   // isotropic position sd per step, metres
    // Isotropic position sd per second between frames (metres per second: a velocity error that
    // persists, e.g. wind the odometry does not see), added in quadrature to eps_tran_m when the
    // frame times are known (FilterInput::dt_s). 0: noise follows the step count and the distance only.
    double eps_tran_m_per_s = 0.0;
    double eps_rot_deg = 2.0;  // heading sd around the measured heading, degrees
    // Without a compass (yaw in the particle state):
    double yaw_sd_deg = 1.0;          // yaw sd added per step to the odometry's rotation increment, degrees
    double yaw_turn_sd = 0.05;        // extra yaw sd per radian the odometry turned (its rotation's scale error)
    double yaw_unknown_sd_deg = 10.0; // yaw sd per step when the rotation is unknown (odometry lost)

    void validate() const;  // throws trn::Error naming the field and its range
};

// One step's motion as every particle sees it.
struct StepMotion {
    double distance_px = 0;        // delta_tran, map pixels
    double course_offset_rad = 0;  // delta_c: direction of the increment minus the measured heading
    double east_px = 0, north_px = 0;  // the increment itself (map pixels; north = -y)
    double heading_rad = 0;        // measured heading this step
    bool have_heading = false;     // false: each particle keeps its own heading
    double turn_rad = 0;           // |heading change| since the previous step
    double heading_change_rad = 0; // the same, signed (clockwise; 0 when unknown): delta_rot of eq. 2.11
    double noise_gain = 1;         // > 1 while the odometry is lost (constant velocity)
    double diffusion_px = 0;       // extra isotropic position sd (ours, lost odometry in a turn: where it went is unknown)
    double time_sd_px = 0;         // eps_tran_m_per_s * the time since the previous frame (ours; 0: unknown or off)
    // Without a compass: each particle turns by rotation_rad (NaN: unknown) and moves by the
    // increment as seen from its own yaw before the turn (the increment is in the previous frame's axes).
    bool yaw_state = false;
    double rotation_rad = NAN;
};

// `frame_heading_rad`: the heading the increment is expressed against (this step's, or the last
// known one when this step has none; NaN: none ever, the increment is taken as forward).
StepMotion make_step_motion(double east_m, double north_m, double heading_rad, double frame_heading_rad, double turn_rad,
                            double metres_per_pixel);

// Moves one particle (x, y map pixels, yaw radians). `z`: five independent standard normal draws
// (heading, along track, course, x, y); all zero = the noise-free motion.
// The step of a filter without a compass: (right_m, forward_m) in the previous frame's axes, the
// frame's rotation since then (NaN: unknown).
StepMotion make_yaw_state_motion(double right_m, double forward_m, double rotation_rad, double metres_per_pixel);

void propagate_particle(const MotionModel& model, const StepMotion& m, double metres_per_pixel, const std::array<double, 5>& z,
                        double& x, double& y, double& yaw);

}  // namespace trn::filter
TRN_API_END
