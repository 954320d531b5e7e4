// The online Localizer's defaults as the C++ library and the C API give them, one JSON line each
// ({"cxx": ..., "c": ...}) for the profile named by argv[1]: tests/python/test_defaults.py compares
// them with Python's and the CLI's (docs/EMBEDDING.md, "Defaults").
#include <cmath>
#include <cstdio>
#include <string>

#include "trn/localize/localizer_defaults.hpp"
#include "trn/localize/localizer_settings.hpp"
#include "trn/trnkit.h"

namespace {
std::string num(double v) {
    if (!std::isfinite(v)) return "null";
    char buf[40];
    std::snprintf(buf, sizeof buf, "%.17g", v);
    return buf;
}
std::string str(const char* s) { return s ? "\"" + std::string(s) + "\"" : "null"; }  // NULL: the library's default
}  // namespace

int main(int argc, char** argv) {
    const std::string profile = argc > 1 ? argv[1] : "ours";
    const trn::localize::LocalizerConfig cxx = trn::localize::localizer_profile(trn::filter::parse_profile(profile));
    trn_localizer_config c;
    if (trn_localizer_config_for_profile(profile.c_str(), &c) != TRN_OK) return 1;
    std::printf("{\"cxx\": %s, \"c\": {", trn::localize::settings_json(cxx, {{"backend", trn::localize::kDefaultBackend}, {"profile", profile}},
                                                                       {{"rate_hz", trn::localize::kDefaultRateHz}})
                                               .c_str());
    std::printf("\"profile\": %s, \"seed\": %s, \"conversion\": %s, \"sampling\": %s, \"heading\": %s, ", str(c.profile).c_str(),
                num(double(c.seed)).c_str(), str(c.conversion).c_str(), str(c.sampling).c_str(), str(c.heading).c_str());
    std::printf("\"min_particles\": %zu, \"max_particles\": %zu, \"particles\": %zu, \"compassless_max_particles\": %zu, ", c.min_particles,
                c.max_particles, c.particles, c.compassless_max_particles);
    std::printf("\"init_radius_m\": %s, \"reinit_radius_m\": %s, \"start_heading_sd_deg\": %s, \"compassless_yaw_sd_deg\": %s, ",
                num(c.init_radius_m).c_str(), num(c.reinit_radius_m).c_str(), num(c.start_heading_sd_deg).c_str(),
                num(c.compassless_yaw_sd_deg).c_str());
    std::printf("\"lock_monitor\": %s, \"max_tilt_deg\": %s, \"template_width\": %d, \"sparse\": %s, \"camera_hfov_deg\": %s, "
                "\"start_heading_rad\": %s, \"visual_odometry\": %s}}\n",
                c.lock_monitor ? "true" : "false", num(c.max_tilt_deg).c_str(), c.template_width, num(c.sparse).c_str(),
                num(c.camera_hfov_deg).c_str(), num(c.start_heading_rad).c_str(), c.visual_odometry ? "true" : "false");
    return 0;
}
