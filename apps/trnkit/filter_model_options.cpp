#include "filter_model_options.hpp"

#include <cmath>
#include <sstream>
#include <string>

#include "trn/error.hpp"

namespace trn::cli {
namespace {

void check(double v, double lo, double hi, const char* option) {
    if (!(std::isfinite(v) && v >= lo && v <= hi)) {
        std::ostringstream os;
        os << option << " " << v << ": must be a finite number in [" << lo << ", " << hi << "]";
        throw Error(os.str());
    }
}

}  // namespace

void add_filter_model_options(CLI::App& cmd, FilterModelArgs& a) {
    cmd.add_option("--motion-alpha1", a.motion.alpha1, "Motion model: along-track sd per metre moved (eq. 2.7 alpha1)")->capture_default_str();
    cmd.add_option("--motion-alpha2", a.motion.alpha2, "Motion model: course sd in radians (across-track sd per metre moved, alpha2)")
        ->capture_default_str();
    cmd.add_option("--motion-alpha3", a.motion.alpha3, "Motion model: extra course sd per radian turned in a step (alpha3)")
        ->capture_default_str();
    cmd.add_option("--motion-eps-tran", a.motion.eps_tran_m, "Motion model: position sd per step, metres (eps_tran)")->capture_default_str();
    cmd.add_option("--motion-eps-rot", a.motion.eps_rot_deg, "Motion model: heading sd around the measured heading, degrees (eps_rot)")
        ->capture_default_str();
    cmd.add_flag("--motion-along-heading", a.along_heading,
                 "Literal eqs. 2.7-2.9: move the odometry's distance along the heading, ignoring its direction");
    cmd.add_option("--lock-min-contrast", a.lock.min_contrast,
                   "Lock monitor: best NCC must beat random places by this many of their sd")
        ->capture_default_str();
    cmd.add_option("--lock-drift", a.lock.drift_fraction, "Lock monitor: allowed departure from dead reckoning per metre flown")
        ->capture_default_str();
    cmd.add_option("--lock-widen-radius", a.lock.widen_radius_m, "Lock monitor: radius (m) of the wider search when lost")
        ->capture_default_str();
    cmd.add_flag("--no-lock-monitor", a.no_lock_monitor, "Do not watch for a wrong lock (no probes, no wider search)");
}

void check_filter_model_options(const FilterModelArgs& a) {
    check(a.motion.alpha1, 0, 1, "--motion-alpha1");
    check(a.motion.alpha2, 0, 1, "--motion-alpha2");
    check(a.motion.alpha3, 0, 5, "--motion-alpha3");
    check(a.motion.eps_tran_m, 0, 1000, "--motion-eps-tran");
    check(a.motion.eps_rot_deg, 0, 180, "--motion-eps-rot");
    check(a.lock.min_contrast, 0, 100, "--lock-min-contrast");
    check(a.lock.drift_fraction, 0, 10, "--lock-drift");
    check(a.lock.widen_radius_m, 0, 1e5, "--lock-widen-radius");
}

void apply_filter_model_options(const FilterModelArgs& a, filter::FilterConfig& c) {
    check_filter_model_options(a);
    c.motion = a.motion;
    c.motion.along_heading = a.along_heading;
    c.lock = a.lock;
    c.lock.enabled = !a.no_lock_monitor;
}

}  // namespace trn::cli
