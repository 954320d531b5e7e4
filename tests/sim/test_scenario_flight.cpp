// Scenario presets, trajectories and the in-memory flight stream.
#include <gtest/gtest.h>

#include <cmath>
#include <set>

#include "sim_test_maps.hpp"
#include "trn/registry.hpp"
#include "trn/sim/flight.hpp"
#include "trn/detail/angles.hpp"

namespace trn::sim {
namespace {

TEST(Scenario, TwelvePresetsNamedLikeTheDatasetAndTheirWindTwins) {
    const auto& presets = scenario_presets();
    ASSERT_EQ(presets.size(), 36u);  // and the -long twins: test_long_presets.cpp
    std::set<std::string> names;
    for (const Scenario& s : presets) {
        names.insert(s.name);
        EXPECT_NEAR(s.speed_mps, 12, 1e-9);
        if (!s.one_loop) {
            EXPECT_EQ(s.frame_count(), 16000u);
        }
    }
    for (const char* n : {"FL-200", "FL-300", "FR-200", "FC-300", "UL-200", "UR-300", "UC-300"}) {
        EXPECT_TRUE(names.count(n)) << n;
        EXPECT_TRUE(names.count(std::string(n) + "-wind")) << n;
        EXPECT_TRUE(names.count(std::string(n) + "-long")) << n;
        EXPECT_EQ(find_scenario(n).realism.crab_max_deg, 0) << "the AIR presets keep the dataset's idealised world";
        EXPECT_EQ(find_scenario(n).realism.altitude_change, 0);
        EXPECT_EQ(find_scenario(std::string(n) + "-wind").realism.crab_max_deg, 30);
        EXPECT_EQ(find_scenario(std::string(n) + "-wind").altitude_m, find_scenario(n).altitude_m);
    }
    EXPECT_EQ(find_scenario("UC-300").terrain, TerrainStyle::Urban);
    EXPECT_EQ(find_scenario("UC-300").shape, TrajectoryShape::Circle);
    EXPECT_EQ(find_scenario("FL-200").altitude_m, 200);
    try {
        find_scenario("XX-100");
        FAIL() << "no throw";
    } catch (const Error& e) {
        EXPECT_NE(std::string(e.what()).find("UC-300"), std::string::npos) << e.what();
    }
}

TEST(Trajectory, StaysInItsAreaAtConstantSpeedWithMatchingHeading) {
    for (TrajectoryShape shape : {TrajectoryShape::Line, TrajectoryShape::Rectangle, TrajectoryShape::Circle}) {
        const Trajectory t(shape, 1600, 12, 100, 150, 700, 650);  // smaller than nominal: shrunk to fit
        double max_rate = 0;
        for (double time = 0; time < 600; time += 0.5) {
            const TrajectoryState a = t.at(time), b = t.at(time + 0.1);
            EXPECT_GE(a.x_m, 100 - 1e-6);
            EXPECT_LE(a.x_m, 700 + 1e-6);
            EXPECT_GE(a.y_m, 150 - 1e-6);
            EXPECT_LE(a.y_m, 650 + 1e-6);
            EXPECT_NEAR(std::hypot(b.x_m - a.x_m, b.y_m - a.y_m), 1.2, 0.02);
            // Heading is the compass direction of travel (north = -y).
            const double travel = std::atan2(b.x_m - a.x_m, -(b.y_m - a.y_m));
            EXPECT_NEAR(wrap_angle(travel - a.heading_rad), 0, 0.1);
            max_rate = std::max(max_rate, std::abs(a.yaw_rate_rad_s));
        }
        if (shape == TrajectoryShape::Circle) {
            EXPECT_GT(t.at(0).yaw_rate_rad_s, 0);  // clockwise on the map
        }
        EXPECT_GT(max_rate, 0.01);
    }
}

TEST(Flight, StreamsFramesWithConsistentTruthAndSensors) {
    const Map& map = testing::urban_map();
    FlightConfig cfg;
    cfg.scenario = find_scenario("UC-200");
    cfg.frames = 6;
    FlightSimulator sim(map, cfg);
    ASSERT_EQ(sim.frame_count(), 6u);
    auto backend = default_registry().create("cpu");
    const MapHandle handle = backend->upload_map(map.image.view());
    FlightFrame f, first;
    int n = 0;
    while (sim.next(f)) {
        if (n == 0) first = f;
        EXPECT_EQ(f.index, std::size_t(n));
        EXPECT_NEAR(f.time_s, n / 50.0, 1e-12);
        EXPECT_EQ(f.image.width, 640);
        EXPECT_NEAR(f.template_scale, template_scale(cfg.camera, 200, 1.0), 1e-12);
        EXPECT_NEAR(f.position_m.x, (f.truth.map_x - first.truth.map_x) * map.metres_per_pixel, 1e-9);
        EXPECT_NEAR(f.position_m.y, -(f.truth.map_y - first.truth.map_y) * map.metres_per_pixel, 1e-9);
        EXPECT_LE(std::abs(wrap_angle(f.magnetometer_heading_rad - f.truth.yaw_rad)), 2 * kDeg + 1e-9);
        const Pose pose = f.truth_pose();
        ParticleScore s;
        backend->score(handle, f.image.view(), std::span<const Pose>(&pose, 1), ScoreOptions{}, std::span<ParticleScore>(&s, 1));
        EXPECT_GT(s.ncc, 0.9) << "frame " << n;
        ++n;
    }
    EXPECT_EQ(n, 6);
    EXPECT_FALSE(sim.next(f));
}

TEST(Flight, WholeFlightWithoutImagesHasPlausibleDrift) {
    const Map& map = testing::forest_map();
    auto final_error = [&](const char* name) {
        FlightConfig cfg;
        cfg.scenario = find_scenario(name);
        cfg.render_images = false;
        cfg.frames = 50 * 120;
        FlightSimulator sim(map, cfg);
        FlightFrame f;
        double err = 0;
        int rows = 0;
        while (sim.next(f)) {
            EXPECT_TRUE(f.image.pixels.empty());
            err = std::hypot(f.odometry_m.x - f.position_m.x, f.odometry_m.y - f.position_m.y);
            ++rows;
        }
        EXPECT_EQ(rows, 50 * 120);
        return err;
    };
    const double circle = final_error("FC-200");
    EXPECT_GT(circle, 1.0);  // drift exists
    EXPECT_LT(circle, 200);  // but stays plausible over 1.4 km
}

TEST(Flight, SameSeedSameFlight) {
    const Map& map = testing::forest_map();
    FlightConfig cfg;
    cfg.scenario = find_scenario("FR-300");
    cfg.frames = 2;
    cfg.camera_roll_pitch_sd_deg = 1;
    FlightSimulator a(map, cfg), b(map, cfg);
    FlightFrame fa, fb;
    while (a.next(fa) && b.next(fb)) {
        EXPECT_EQ(fa.image.pixels, fb.image.pixels);
        EXPECT_EQ(fa.odometry_m.x, fb.odometry_m.x);
        EXPECT_NE(fa.truth.roll_rad, 0);
    }
}

TEST(Flight, MapTooSmallForTheFootprintThrows) {
    Map tiny;
    tiny.image = {200, 200, std::vector<std::uint8_t>(200 * 200, 100)};
    FlightConfig cfg;
    cfg.scenario = find_scenario("FL-300");
    EXPECT_THROW(FlightSimulator(tiny, cfg), Error);
}

}  // namespace
}  // namespace trn::sim
