#include "trn/localize/localizer_settings.hpp"

#include <cmath>

#include <nlohmann/json.hpp>

#include "trn/io/outside_text.hpp"

namespace trn::localize {
namespace {
nlohmann::json number(double v) { return std::isfinite(v) ? nlohmann::json(v) : nlohmann::json(nullptr); }
}  // namespace

std::string settings_json(const LocalizerConfig& c, const std::map<std::string, std::string>& strings,
                          const std::map<std::string, double>& numbers) {
    const filter::FilterConfig& f = c.filter;
    nlohmann::json j = nlohmann::json::object();
    for (const auto& [k, v] : strings) j[k] = v;
    for (const auto& [k, v] : numbers) j[k] = number(v);
    j["seed"] = f.seed;
    j["conversion"] = f.conversion.to_string();
    j["sampling"] = filter::to_string(f.sampling);
    j["min_particles"] = f.min_particles, j["max_particles"] = f.max_particles, j["particles"] = f.fixed_particles;
    j["compassless_max_particles"] = c.compassless_max_particles;
    j["init_radius_m"] = number(f.init_radius_m), j["reinit_radius_m"] = number(f.reinit_radius_m);
    j["start_heading_sd_deg"] = number(f.init_heading_sd_deg), j["compassless_yaw_sd_deg"] = number(c.compassless_yaw_sd_deg);
    j["heading"] = filter::to_string(f.heading);
    j["lock_monitor"] = f.lock.enabled;
    j["max_tilt_deg"] = number(c.max_tilt_deg);
    j["template_width"] = c.scoring.template_width;
    j["sparse"] = c.scoring.sampling.kind == Sampling::Kind::Random ? c.scoring.sampling.fraction : 1.0;
    j["camera_hfov_deg"] = number(c.camera_hfov_deg), j["start_heading_rad"] = number(c.start_heading_rad);
    j["visual_odometry"] = c.visual_odometry;
    return io::json_line(j);
}

}  // namespace trn::localize
