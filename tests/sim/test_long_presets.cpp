// The "-long" presets (issue 17): the dissertation's flight distances (Table 2.2) in one loop,
// with climbs and descents between the family's two altitudes, on a map that holds the loop.
#include <gtest/gtest.h>

#include <cmath>

#include "trn/sim/altitude_profile.hpp"
#include "trn/sim/flight.hpp"

namespace trn::sim {
namespace {

// Table 2.2 of the dissertation: flight distance in metres.
struct Published {
    const char* name;
    double distance_m;
};
const Published kTable22[12] = {{"FL-200", 2936}, {"FL-300", 2736}, {"FR-200", 4748}, {"FR-300", 4541}, {"FC-200", 1065}, {"FC-300", 1028},
                                {"UL-200", 2592}, {"UL-300", 2496}, {"UR-200", 4418}, {"UR-300", 4542}, {"UC-200", 1016}, {"UC-300", 970}};

// A blank map of the given edge at 4 m/px: only its size matters when no image is rendered.
Map blank_map(double edge_m) {
    Map m;
    m.metres_per_pixel = 4;
    m.image.width = m.image.height = static_cast<int>(std::ceil(edge_m / 4));
    m.image.pixels.assign(std::size_t(m.image.width) * m.image.height, 128);
    return m;
}

// Flown over the map fitting_map_edge_m gives, each -long flight covers its Table 2.2 distance
// within 1 % (the loop polyline and the 1 m heading look-ahead), ends where it started (one whole
// loop: it was not shrunk to fit) and changes altitude between 200 and 300 m at a climb rate a
// small fixed-wing UAV manages (peak 3.9 m/s for 100 m in 40 s with the cosine profile).
TEST(LongPresets, FlyTable22DistancesInOneLoopWithClimbsBetween200And300m) {
    for (const Published& p : kTable22) {
        const Scenario& base = find_scenario(p.name);
        const Scenario& s = find_scenario(std::string(p.name) + "-long");
        EXPECT_EQ(s.shape, base.shape) << s.name;
        EXPECT_EQ(s.terrain, base.terrain) << s.name;
        EXPECT_EQ(s.realism.crab_max_deg, 0) << "the AIR world otherwise";
        EXPECT_NEAR(s.distance_m(), p.distance_m, 1e-6) << s.name;
        FlightConfig cfg;
        cfg.scenario = s;
        cfg.render_images = false;
        const Map map = blank_map(fitting_map_edge_m(cfg));
        FlightSimulator flight(map, cfg);
        FlightFrame f, first;
        double path_m = 0, px = 0, py = 0, alt_min = 1e9, alt_max = 0, prev_alt = 0, max_rate = 0;
        while (flight.next(f)) {
            const double x = f.truth.map_x * map.metres_per_pixel, y = f.truth.map_y * map.metres_per_pixel;
            if (f.index == 0) {
                first = f;
            } else {
                path_m += std::hypot(x - px, y - py);
                max_rate = std::max(max_rate, std::abs(f.truth.altitude_m - prev_alt) * s.fps);
            }
            // The localizer's template scale follows the altitude (exact barometer in this world).
            EXPECT_NEAR(measured_template_scale(f, cfg.camera, map.metres_per_pixel), f.template_scale, 1e-9);
            px = x, py = y, prev_alt = f.truth.altitude_m;
            alt_min = std::min(alt_min, f.truth.altitude_m), alt_max = std::max(alt_max, f.truth.altitude_m);
        }
        EXPECT_NEAR(path_m, p.distance_m, 0.01 * p.distance_m) << s.name;
        EXPECT_LT(std::hypot(f.truth.map_x - first.truth.map_x, f.truth.map_y - first.truth.map_y) * map.metres_per_pixel, 15)
            << s.name << ": the flight is one whole loop";
        EXPECT_EQ(first.truth.altitude_m, base.altitude_m) << s.name << " starts at its own altitude";
        EXPECT_NEAR(alt_min, 200, 0.01) << s.name;
        EXPECT_NEAR(alt_max, 300, 0.01) << s.name;
        EXPECT_LT(max_rate, 4.0) << s.name;
        EXPECT_GT(max_rate, 3.5) << s.name;
    }
}

TEST(LongPresets, LongerFlightsChangeAltitudeMoreOftenAndTheProfileNeverJumps) {
    const AltitudeProfile circle(find_scenario("FC-200-long")), rectangle(find_scenario("FR-200-long"));
    EXPECT_EQ(circle.changes(), 1);     // 89 s: one climb between two level legs
    EXPECT_EQ(rectangle.changes(), 4);  // 396 s: up, down, up, down
    EXPECT_EQ(AltitudeProfile(find_scenario("FR-200")).changes(), 0);
    EXPECT_EQ(AltitudeProfile(find_scenario("FR-200")).altitude_m(100), 200);
    // Flown past its end (a longer --distance-km) the profile runs backwards: continuous.
    const double d = find_scenario("FC-200-long").duration_s;
    for (double t = 0; t < 3 * d; t += 0.02) EXPECT_LT(std::abs(circle.altitude_m(t + 0.02) - circle.altitude_m(t)), 0.1) << t;
}

TEST(LongPresets, MapEdgeKeepsTheRuleOfTheOtherPresets) {
    // The AIR and -wind presets keep 1.1 x nominal size + footprint diameter at the highest altitude + 100 m.
    FlightConfig cfg;
    cfg.scenario = find_scenario("FR-200-wind");
    const double footprint = cfg.scenario.max_altitude_m() / cfg.camera.focal_px() * 400 * 2;
    EXPECT_EQ(fitting_map_edge_m(cfg), std::ceil((1100 * 1.1 + footprint + 100) / 100) * 100);
}

}  // namespace
}  // namespace trn::sim
