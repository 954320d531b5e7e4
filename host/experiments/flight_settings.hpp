#pragma once
// What every flight study (study_flights.cpp, study_long_flights.cpp) writes into its configuration
// about the filter: its defaults by name, so that job files made with an older filter (before the
// displacement-vector motion model, the lock monitor or its fix rule) are refused, not mixed.
#include <string>
#include <vector>

#include "study.hpp"

namespace trn::experiments {

inline constexpr const char* kFilterDefaults =
    "defaults: KLD (eps 0.05, q 0.9, 5 m bins, 100..2000), motion along the odometry's displacement vector "
    "(alpha 0.05/0.03/0.2, eps 1 m/2 deg), lock monitor on (48 probes, contrast 3/5.5, fix +5.5 per drift bound from "
    "dead reckoning, held 3 steps)";

// The same for --profile dissertation (filter::dissertation_profile, particle_filter.hpp): replaces
// the study's "filter" text in the configuration.
inline constexpr const char* kDissertationFilter =
    "dissertation profile: KLD (eps 0.05, delta 0.9 read as z = -1.28, 5 m bins, 100..100000 (no maximum in the text: "
    "a safety cap), 500-particle initial set), eqs. 2.7-2.11 as printed (alpha 1, eps 3 m / 6 deg as 3 sd of "
    "sample_normal), no lock monitor";

// One job per (preset, run) of c["presets"] x c["runs"], ids "<preset>-<run>": the odometry studies'
// job list (study_flights.cpp, study_long_flights.cpp).
inline std::vector<Json> preset_run_jobs(const Json& c) {
    std::vector<Json> out;
    for (const auto& p : c.at("presets").get<std::vector<std::string>>())
        for (int r = 0; r < c.at("runs").get<int>(); ++r) out.push_back({{"id", p + "-" + std::to_string(r)}, {"preset", p}, {"run", r}});
    return out;
}

}  // namespace trn::experiments
