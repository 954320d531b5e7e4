#pragma once
// Maps shared by the simulator tests: generated once per test binary (they take a second).
#include <cstdlib>
#include <filesystem>
#include <optional>
#include <string>

#include "trn/error.hpp"
#include "trn/sim/procedural_map.hpp"
#include "../common/shared_data.hpp"

namespace trn::sim::testing {

inline ProceduralMapOptions small_map_options(TerrainStyle style, int year = 2008) {
    ProceduralMapOptions o;
    o.style = style;
    o.seed = 11;
    o.year = year;
    o.width_m = o.height_m = 640;
    return o;
}

inline const Map& urban_map() {
    static const Map map = generate_procedural_map(small_map_options(TerrainStyle::Urban));
    return map;
}

inline const Map& forest_map() {
    static const Map map = generate_procedural_map(small_map_options(TerrainStyle::Forest));
    return map;
}

// The real orthophoto from TRN_SHARED_DATA, when present.
inline std::optional<std::string> real_orthophoto() {
    const std::string path = trn::test::shared_data("orthophoto.png");
    if (path.empty()) return std::nullopt;
    return path;
}

}  // namespace trn::sim::testing
