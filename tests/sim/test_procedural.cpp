// The procedural orthophoto: deterministic, tile-consistent, textured like aerial imagery, and
// changed (but recognisably the same place) in a later year.
#include <gtest/gtest.h>

#include <chrono>
#include <cmath>
#include <cstdio>

#include "sim_test_maps.hpp"
#include "trn/sim/map_ageing.hpp"

namespace trn::sim {
namespace {

double mean_abs_diff(const GrayImage& a, const GrayImage& b) {
    double s = 0;
    for (std::size_t i = 0; i < a.pixels.size(); ++i) s += std::abs(int(a.pixels[i]) - int(b.pixels[i]));
    return s / a.pixels.size();
}

TEST(ProceduralMap, SameSeedSameMapOtherSeedOtherMap) {
    ProceduralMapOptions o = testing::small_map_options(TerrainStyle::Forest);
    o.width_m = o.height_m = 300;
    const Map a = generate_procedural_map(o), b = generate_procedural_map(o);
    EXPECT_EQ(a.image.pixels, b.image.pixels);
    EXPECT_EQ(a.image.width, 300);
    EXPECT_DOUBLE_EQ(a.metres_per_pixel, 1.0);
    ASSERT_TRUE(a.origin.has_value());
    o.seed = 12;
    EXPECT_GT(mean_abs_diff(a.image, generate_procedural_map(o).image), 10);
}

TEST(ProceduralMap, RegionEqualsCropOfTheWholeMap) {
    const Map& whole = testing::urban_map();
    const ProceduralMapOptions o = testing::small_map_options(TerrainStyle::Urban);
    const GrayImage tile = generate_procedural_region(o, 317, 201, 128, 96);
    for (int y = 0; y < tile.height; ++y)
        for (int x = 0; x < tile.width; ++x)
            ASSERT_EQ(tile.pixels[y * tile.width + x], whole.image.pixels[(y + 201) * whole.image.width + x + 317])
                << "at " << x << "," << y;
}

// Local contrast (mean absolute Sobel-like difference) and overall spread of grey levels: aerial
// imagery has both; a flat or pure-noise image fails one of them.
TEST(ProceduralMap, BothStylesAreTexturedAndDiffer) {
    for (const Map* m : {&testing::urban_map(), &testing::forest_map()}) {
        const GrayImage& g = m->image;
        double sum = 0, sum2 = 0, grad = 0;
        int dark = 0, bright = 0;
        for (int y = 0; y + 1 < g.height; ++y)
            for (int x = 0; x + 1 < g.width; ++x) {
                const int p = g.pixels[y * g.width + x];
                sum += p, sum2 += double(p) * p;
                grad += std::abs(p - g.pixels[y * g.width + x + 1]);
                dark += p < 60, bright += p > 170;
            }
        const double n = double(g.height - 1) * (g.width - 1), sd = std::sqrt(sum2 / n - (sum / n) * (sum / n));
        EXPECT_GT(sd, 25);
        EXPECT_GT(grad / n, 4);
        EXPECT_GT(dark, n * 0.01);
        EXPECT_GT(bright, n * 0.005);
    }
    EXPECT_GT(mean_abs_diff(testing::urban_map().image, testing::forest_map().image), 20);
}

TEST(ProceduralMap, LaterYearChangesTheMapButKeepsThePlace) {
    ProceduralMapOptions o = testing::small_map_options(TerrainStyle::Forest);
    o.width_m = o.height_m = 400;
    const Map a = generate_procedural_map(o);
    o.year = 2014;
    const Map b = generate_procedural_map(o);
    const double diff = mean_abs_diff(a.image, b.image);
    EXPECT_GT(diff, 5);
    // Same place: correlation of the two maps stays clearly positive.
    double sa = 0, sb = 0, sab = 0, saa = 0, sbb = 0;
    const double n = double(a.image.pixels.size());
    for (std::size_t i = 0; i < a.image.pixels.size(); ++i) {
        const double x = a.image.pixels[i], y = b.image.pixels[i];
        sa += x, sb += y, sab += x * y, saa += x * x, sbb += y * y;
    }
    const double r = (sab - sa * sb / n) / std::sqrt((saa - sa * sa / n) * (sbb - sb * sb / n));
    EXPECT_GT(r, 0.4);
}

TEST(ProceduralMap, InvalidOptionsThrow) {
    ProceduralMapOptions o;
    o.metres_per_pixel = 0;
    EXPECT_THROW(generate_procedural_map(o), Error);
    o = {};
    o.width_m = 1;
    EXPECT_THROW(generate_procedural_map(o), Error);
    EXPECT_THROW(parse_terrain_style("desert"), Error);
    EXPECT_EQ(parse_terrain_style("urban"), TerrainStyle::Urban);
}

// Generation speed, reported (not asserted: the test machine is shared): 1 km^2 at 1 m/px.
TEST(ProceduralMap, GenerationSpeedIsReported) {
    ProceduralMapOptions o = testing::small_map_options(TerrainStyle::Urban);
    o.width_m = o.height_m = 1000;
    const auto t0 = std::chrono::steady_clock::now();
    const Map m = generate_procedural_map(o);
    const double s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    std::printf("procedural urban 1000x1000 px: %.3f s (%.1f Mpx/s)\n", s, 1.0 / s);
    EXPECT_EQ(m.image.pixels.size(), 1000u * 1000u);
}

TEST(MapAgeing, KeepsGeometryAndChangesContent) {
    const Map& base = testing::forest_map();
    MapAgeingOptions o;
    o.years = 6;
    const Map a = age_map(base, o), b = age_map(base, o);
    EXPECT_EQ(a.image.pixels, b.image.pixels);  // seeded
    EXPECT_EQ(a.image.width, base.image.width);
    EXPECT_EQ(a.metres_per_pixel, base.metres_per_pixel);
    EXPECT_GT(mean_abs_diff(a.image, base.image), 4);
    o.years = 0;
    EXPECT_LT(mean_abs_diff(age_map(base, o).image, base.image), 0.5);
    o.years = -1;
    EXPECT_THROW(age_map(base, o), Error);
}

}  // namespace
}  // namespace trn::sim
