#include "filter_model_options.hpp"

#include "options.hpp"

namespace trn::cli {

void add_filter_model_options(CLI::App& cmd, FilterModelArgs& a) {
    cmd.add_option("--motion-alpha1", a.motion.alpha1, "Motion model: along-track sd per metre moved (eq. 2.7 alpha1)")->check(real_in(0, 1))->capture_default_str();
    cmd.add_option("--motion-alpha2", a.motion.alpha2, "Motion model: course sd in radians (across-track sd per metre moved, alpha2)")
        ->check(real_in(0, 1))->capture_default_str();
    cmd.add_option("--motion-alpha3", a.motion.alpha3, "Motion model: extra course sd per radian turned in a step (alpha3)")
        ->check(real_in(0, 5))->capture_default_str();
    cmd.add_option("--motion-eps-tran", a.motion.eps_tran_m, "Motion model: position sd per step, metres (eps_tran)")->check(real_in(0, 1000))->capture_default_str();
    cmd.add_option("--motion-eps-rot", a.motion.eps_rot_deg, "Motion model: heading sd around the measured heading, degrees (eps_rot)")
        ->check(real_in(0, 180))->capture_default_str();
    cmd.add_option("--motion-yaw-sd", a.motion.yaw_sd_deg, "Motion model, --heading none: yaw sd added per step to the odometry's rotation, degrees")
        ->check(real_in(0, 180))->capture_default_str();
    cmd.add_option("--motion-yaw-turn-sd", a.motion.yaw_turn_sd, "Motion model, --heading none: extra yaw sd per radian the odometry turned")
        ->check(real_in(0, 5))->capture_default_str();
    cmd.add_option("--motion-yaw-unknown-sd", a.motion.yaw_unknown_sd_deg,
                   "Motion model, --heading none: yaw sd per step when the odometry's rotation is unknown (lost), degrees")
        ->check(real_in(0, 180))->capture_default_str();
    cmd.add_flag("--motion-along-heading", a.along_heading,
                 "Literal eqs. 2.7-2.9: move the odometry's distance along the heading, ignoring its direction");
    cmd.add_option("--lock-min-contrast", a.lock.min_contrast,
                   "Lock monitor: best NCC must beat random places by this many of their sd")
        ->check(real_in(0, 100))->capture_default_str();
    cmd.add_option("--lock-drift", a.lock.drift_fraction, "Lock monitor: allowed departure from dead reckoning per metre flown")
        ->check(real_in(0, 10))->capture_default_str();
    cmd.add_option("--lock-widen-radius", a.lock.widen_radius_m, "Lock monitor: radius (m) of the wider search when lost")
        ->check(real_in(0, 1e5))->capture_default_str();
    cmd.add_flag("--no-lock-monitor", a.no_lock_monitor, "Do not watch for a wrong lock (no probes, no wider search)");
}

void apply_filter_model_options(const FilterModelArgs& a, filter::FilterConfig& c) {
    c.motion = a.motion;
    c.motion.along_heading = a.along_heading;
    c.lock = a.lock;
    c.lock.enabled = !a.no_lock_monitor;
}

}  // namespace trn::cli
