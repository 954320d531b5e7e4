#pragma once
// Ages an arbitrary map image by some years, so a flight can be rendered from one map and
// localized on another: season / brightness shift, large-scale illumination change, vegetation
// patches that changed, new buildings with shadows in a new sun direction, removed buildings
// (small patches smoothed away). Geometry is unchanged, so the same pixel is the same place.
// (Procedural maps age exactly by generating them for another year; see procedural_map.hpp.)
#include <cstdint>

#include "trn/sim/map.hpp"
#include "trn/export.hpp"

TRN_API_BEGIN
namespace trn::sim {

struct MapAgeingOptions {
    double years = 6;          // strength grows with the years, saturating at about 8
    std::uint64_t seed = 1;
    double building_size_m = 10;  // typical new house footprint edge
    double new_buildings_per_km2_per_year = 4;
    double vegetation_change_share_per_year = 0.02;  // share of the area whose vegetation changes
};

Map age_map(const Map& map, const MapAgeingOptions& options);

}  // namespace trn::sim
TRN_API_END
