#include "trn/localize/localizer_defaults.hpp"

#include <algorithm>
#include <cmath>

namespace trn::localize {

LocalizerConfig localizer_profile(filter::Profile profile) {
    LocalizerConfig c;
    c.filter = filter::profile_config(profile);
    c.compassless_yaw_sd_deg = kCompasslessYawSdDeg;
    c.visual_odometry = kDefaultVisualOdometry;
    if (profile == filter::Profile::Ours) {
        c.filter.init_radius_m = kHandoverInitRadiusM;
        c.compassless_max_particles = kCompasslessUniformMaxParticles;
    }
    return c;
}

LocalizerConfig resolved_config(const LocalizerConfig& config) {
    LocalizerConfig r = config;
    if (r.filter.heading != filter::HeadingMode::None) return r;
    if (std::isnan(r.start_heading_rad))
        r.filter.max_particles = std::max(r.filter.max_particles, r.compassless_max_particles);
    else if (std::isnan(r.filter.init_heading_sd_deg))
        r.filter.init_heading_sd_deg = r.compassless_yaw_sd_deg;
    return r;
}

}  // namespace trn::localize
