#pragma once
// The online Localizer's defaults: one home for every front end. `trnkit localize`, the C API
// (trn_localizer_config_for_profile) and Python (trnkit.Localizer, trnkit.localize,
// trnkit.localizer_defaults) all start from localizer_profile() and take the constants here, so no
// default can drift between them. docs/EMBEDDING.md, "Defaults", has the table (each name in C++, C,
// Python and the CLI); tests/python/test_defaults.py reads it from all four and compares.
#include <cstddef>

#include "trn/filter/particle_filter.hpp"
#include "trn/localize/localizer.hpp"
#include "trn/export.hpp"

TRN_API_BEGIN
namespace trn::localize {

// The start prior under our profile: a handover after GNSS loss, whose last fix is good to metres
// (300 m, the dissertation's, mostly costs mean error). The dissertation profile keeps the text's
// 300 m (FilterConfig::init_radius_m).
inline constexpr double kHandoverInitRadiusM = 50;
// With no compass and a uniform yaw prior the initial set must cover every yaw over the start disc:
// on the real flights 2000 particles missed the 2x-of-the-compass target on 2 seeds of 5, 6000 met it
// on all (docs/RESULTS.md, "Compass-less localization"). Ours only (the dissertation has no such mode).
inline constexpr std::size_t kCompasslessUniformMaxParticles = 6000;
// With no compass and a yaw prior given without its spread: its sd, degrees.
inline constexpr double kCompasslessYawSdDeg = 10;
// The backend a front end makes when none is named: the first usable of GPU OpenCL, GPU Vulkan, cpu,
// other devices (Registry::create_fastest). Estimates agree across backends to ~10 digits.
inline constexpr const char* kDefaultBackend = "fastest";
// Visual odometry online (LocalizerConfig::visual_odometry): off; the caller gives the odometry.
inline constexpr bool kDefaultVisualOdometry = false;
// Filter steps per second of a recorded flight (LocalizationSpec::rate_hz).
inline constexpr double kDefaultRateHz = 5;

// The presets of --profile (filter::Profile; particle_filter.hpp says where each value of the
// dissertation's comes from): the profile's filter, our handover start prior and the compass-less
// rules (ours: kCompasslessUniformMaxParticles; both: kCompasslessYawSdDeg).
LocalizerConfig localizer_profile(filter::Profile profile);
inline LocalizerConfig dissertation_profile() { return localizer_profile(filter::Profile::Dissertation); }

// The config the Localizer runs with: the compass-less rules of LocalizerConfig applied
// (compassless_max_particles, compassless_yaw_sd_deg); every other field as given. Idempotent.
LocalizerConfig resolved_config(const LocalizerConfig& config);

}  // namespace trn::localize
TRN_API_END
