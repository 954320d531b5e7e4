#pragma once
// A procedural orthophoto that looks like aerial imagery: a warped road network, fields with
// row patterns and tramlines, forest made of lit tree crowns, villages / towns with gable-roofed
// houses and their shadows, industrial halls, parks, lakes and a river.
//
// Every pixel is a pure function of (seed, year, position), so any region can be generated on its
// own (tile-wise, on demand) and equals the same crop of the whole map. The `year` is the map's
// acquisition year: it changes the season (brightness, vegetation tone), the sun (shadow direction
// and length), the crops in every field, clear-cut forest and which houses stand — the map ageing
// of a procedural world (see map_ageing.hpp for ageing an arbitrary image).
#include <cstdint>
#include <string_view>

#include "trn/sim/map.hpp"
#include "trn/export.hpp"

TRN_API_BEGIN
namespace trn::sim {

enum class TerrainStyle { Forest, Urban };
TerrainStyle parse_terrain_style(std::string_view text);  // "forest" / "urban"; throws trn::Error
const char* to_string(TerrainStyle style);

struct ProceduralMapOptions {
    TerrainStyle style = TerrainStyle::Forest;
    std::uint64_t seed = 1;
    int year = 2008;
    double width_m = 2000, height_m = 2000;
    double metres_per_pixel = 1.0;
    GeoOrigin origin{47.0, 8.0};

    int width_px() const;
    int height_px() const;
    void validate() const;
};

Map generate_procedural_map(const ProceduralMapOptions& options);
// Pixels [x0, x0+w) x [y0, y0+h) of the map generate_procedural_map would make (may extend past it).
GrayImage generate_procedural_region(const ProceduralMapOptions& options, int x0, int y0, int w, int h);

}  // namespace trn::sim
TRN_API_END
