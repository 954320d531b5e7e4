#pragma once
// A LocalizerConfig's settings as one line of JSON under the names of docs/EMBEDDING.md's defaults
// table (the Python keywords): what `trnkit localize --print-config` and trnkit.localizer_defaults()
// print, so that tests/python/test_defaults.py compares the front ends by name. NaN is null.
#include <map>
#include <string>

#include "trn/localize/localizer.hpp"
#include "trn/export.hpp"

TRN_API_BEGIN
namespace trn::localize {

// seed, conversion, sampling, min_particles, max_particles, particles, compassless_max_particles,
// init_radius_m, reinit_radius_m, start_heading_sd_deg, compassless_yaw_sd_deg, heading,
// lock_monitor, max_tilt_deg, template_width, sparse, camera_hfov_deg, start_heading_rad; plus the
// front end's own members (e.g. {"backend", "fastest"}, {"rate_hz", 5}).
std::string settings_json(const LocalizerConfig& config, const std::map<std::string, std::string>& strings = {},
                          const std::map<std::string, double>& numbers = {});

}  // namespace trn::localize
TRN_API_END
