#include "filter_model_options.hpp"

#include "options.hpp"
#include "trn/error.hpp"

namespace trn::cli {

CLI::Option* add_profile_option(CLI::App& cmd, std::string& profile) {
    return cmd
        .add_option("--profile", profile,
                    "Filter settings: ours (trnkit's reading, the default) or dissertation (the text as written where it is "
                    "unambiguous: KLD z = -1.28, a 500-particle initial set, no particle maximum, eqs. 2.7-2.11 as printed, "
                    "no lock monitor; docs/PROFILES.md)")
        ->capture_default_str()
        ->check(CLI::IsMember({"ours", "dissertation"}));
}

CLI::Option* add_lock_monitor_option(CLI::App& cmd, std::string& lock_monitor) {
    return cmd.add_option("--lock-monitor", lock_monitor, "Watch for a wrong lock and widen the search: on or off (default: the profile's; ours on, dissertation off)")
        ->check(CLI::IsMember({"on", "off"}));
}

void add_filter_model_options(CLI::App& cmd, FilterModelArgs& a) {
    add_profile_option(cmd, a.profile);
    auto given = [&a](const CLI::Option* o, std::function<void(filter::FilterConfig&)> f) { a.given.emplace_back(o, std::move(f)); };
    filter::MotionModel& m = a.motion;
    given(cmd.add_option("--motion-alpha1", m.alpha1, "Motion model: along-track sd per metre moved (ours; dissertation: eq. 2.7's alpha1, a scale)")
              ->check(real_in(0, 1))->capture_default_str(),
          [&m](filter::FilterConfig& c) { c.motion.alpha1 = m.alpha1; });
    given(cmd.add_option("--motion-alpha2", m.alpha2, "Motion model: course sd in radians, across-track sd per metre moved (ours; dissertation: eq. 2.8's alpha2, a scale)")
              ->check(real_in(0, 1))->capture_default_str(),
          [&m](filter::FilterConfig& c) { c.motion.alpha2 = m.alpha2; });
    given(cmd.add_option("--motion-alpha3", m.alpha3, "Motion model: extra course sd per radian turned in a step (ours; dissertation: eq. 2.9's alpha3, a scale)")
              ->check(real_in(0, 5))->capture_default_str(),
          [&m](filter::FilterConfig& c) { c.motion.alpha3 = m.alpha3; });
    given(cmd.add_option("--motion-eps-tran", m.eps_tran_m, "Motion model: position sd per step, metres (ours; dissertation: eps_tran of eq. 2.10, 3 sd)")
              ->check(real_in(0, 1000))->capture_default_str(),
          [&m](filter::FilterConfig& c) { c.motion.eps_tran_m = m.eps_tran_m; });
    given(cmd.add_option("--motion-eps-tran-per-s", m.eps_tran_m_per_s,
                         "Motion model: position sd per second between frames, metres per second, added in quadrature to "
                         "--motion-eps-tran when the frames have times (an AIR folder's TimeS column; ours only)")
              ->check(real_in(0, 100))->capture_default_str(),
          [&m](filter::FilterConfig& c) { c.motion.eps_tran_m_per_s = m.eps_tran_m_per_s; });
    given(cmd.add_option("--motion-eps-rot", m.eps_rot_deg, "Motion model: heading sd around the measured heading, degrees (ours; dissertation: eps_rot of eq. 2.11, 3 sd)")
              ->check(real_in(0, 180))->capture_default_str(),
          [&m](filter::FilterConfig& c) { c.motion.eps_rot_deg = m.eps_rot_deg; });
    given(cmd.add_option("--motion-yaw-sd", m.yaw_sd_deg, "Motion model, --heading none: yaw sd added per step to the odometry's rotation, degrees")
              ->check(real_in(0, 180))->capture_default_str(),
          [&m](filter::FilterConfig& c) { c.motion.yaw_sd_deg = m.yaw_sd_deg; });
    given(cmd.add_option("--motion-yaw-turn-sd", m.yaw_turn_sd, "Motion model, --heading none: extra yaw sd per radian the odometry turned")
              ->check(real_in(0, 5))->capture_default_str(),
          [&m](filter::FilterConfig& c) { c.motion.yaw_turn_sd = m.yaw_turn_sd; });
    given(cmd.add_option("--motion-yaw-unknown-sd", m.yaw_unknown_sd_deg,
                         "Motion model, --heading none: yaw sd per step when the odometry's rotation is unknown (lost), degrees")
              ->check(real_in(0, 180))->capture_default_str(),
          [&m](filter::FilterConfig& c) { c.motion.yaw_unknown_sd_deg = m.yaw_unknown_sd_deg; });
    cmd.add_flag("--motion-along-heading", a.along_heading,
                 "Our motion model without its crab offset: the odometry's distance is moved along the measured heading, its "
                 "direction dropped; the rest stays ours (heading reset to the magnetometer, our alpha roles). Not the "
                 "dissertation's equations: those are --profile dissertation");
    filter::UpdateModel& u = a.update;
    given(cmd.add_option("--update-min-ess", u.min_ess_fraction,
                         "Update: temper each frame's weights so the effective sample size stays at least this share of the "
                         "particles (0: believe every frame whole, the dissertation)")
              ->check(real_in(0, 1))->capture_default_str(),
          [&u](filter::FilterConfig& c) { c.update.min_ess_fraction = u.min_ess_fraction; });
    given(cmd.add_option("--update-unknown", a.update_unknown,
                         "Update: weight of a particle without a valid score (its patch off the map or on no-data): neutral (a "
                         "poor but possible place's, --update-unknown-quantile; ours) or zero (the dissertation)")
              ->check(CLI::IsMember({"neutral", "zero"})),
          [&a](filter::FilterConfig& c) { c.update.unknown_neutral = a.update_unknown == "neutral"; });
    given(cmd.add_option("--update-min-valid", u.min_valid_fraction,
                         "Update: a particle is scored when at least this share of its samples lies on map data (off the map and "
                         "no-data are not); fewer: --update-unknown decides its weight")
              ->check(real_in(0, 1, Open::low))->capture_default_str(),
          [&u](filter::FilterConfig& c) { c.update.min_valid_fraction = u.min_valid_fraction; });
    given(cmd.add_option("--update-unknown-quantile", u.unknown_quantile,
                         "Update: a particle without a valid score gets the weight of this quantile of the valid particles' NCCs "
                         "(with --update-unknown neutral)")
              ->check(real_in(0, 1))->capture_default_str(),
          [&u](filter::FilterConfig& c) { c.update.unknown_quantile = u.unknown_quantile; });
    filter::LockMonitorConfig& l = a.lock;
    given(cmd.add_option("--lock-min-contrast", l.min_contrast, "Lock monitor: best NCC must beat random places by this many of their sd")
              ->check(real_in(0, 100))->capture_default_str(),
          [&l](filter::FilterConfig& c) { c.lock.min_contrast = l.min_contrast; });
    given(cmd.add_option("--lock-drift", l.drift_fraction, "Lock monitor: allowed departure from dead reckoning per metre flown")
              ->check(real_in(0, 10))->capture_default_str(),
          [&l](filter::FilterConfig& c) { c.lock.drift_fraction = l.drift_fraction; });
    given(cmd.add_option("--lock-widen-radius", l.widen_radius_m, "Lock monitor: radius (m) of the wider search when lost")
              ->check(real_in(0, 1e5))->capture_default_str(),
          [&l](filter::FilterConfig& c) { c.lock.widen_radius_m = l.widen_radius_m; });
    add_lock_monitor_option(cmd, a.lock_monitor);
    cmd.add_flag("--no-lock-monitor", a.no_lock_monitor, "Do not watch for a wrong lock (no probes, no wider search); = --lock-monitor off");
}

void check_filter_model_options(const FilterModelArgs& a) {
    if (a.along_heading && filter::parse_profile(a.profile) == filter::Profile::Dissertation)
        throw Error("--motion-along-heading: an option of our motion model; --profile dissertation moves along the heading by its own equations");
    if (a.no_lock_monitor && a.lock_monitor == "on") throw Error("--no-lock-monitor and --lock-monitor on: give one of them");
}

void apply_filter_model_options(const FilterModelArgs& a, filter::FilterConfig& c) {
    check_filter_model_options(a);
    const filter::Profile profile = filter::parse_profile(a.profile);
    c.motion = filter::profile_config(profile).motion;
    c.lock = filter::profile_config(profile).lock;
    c.update = filter::profile_config(profile).update;
    for (const auto& [option, apply] : a.given)
        if (option->count() > 0) apply(c);
    c.motion.along_heading = a.along_heading;
    if (a.no_lock_monitor || a.lock_monitor == "off") c.lock.enabled = false;
    if (a.lock_monitor == "on") c.lock.enabled = true;
}

}  // namespace trn::cli
