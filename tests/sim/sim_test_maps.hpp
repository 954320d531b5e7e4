#pragma once
// Maps shared by the simulator tests: generated once per test binary (they take a second).
#include <cstdlib>
#include <filesystem>
#include <optional>
#include <string>

#include "trn/error.hpp"
#include "trn/sim/procedural_map.hpp"

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
    const char* dir = std::getenv("TRN_SHARED_DATA");
    if (!dir) return std::nullopt;
    const std::string path = std::string(dir) + "/orthophoto.png";
    if (!std::filesystem::exists(path)) return std::nullopt;
    return path;
}

}  // namespace trn::sim::testing
