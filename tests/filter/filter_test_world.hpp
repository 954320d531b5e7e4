#pragma once
// One small procedural world shared by the filter tests: an 800 m forest map (2008) as the
// localization map and the same place two years later as the world the camera sees.
#include "trn/filter/flight_source.hpp"
#include "trn/registry.hpp"
#include "trn/sim/procedural_map.hpp"

namespace trn::filter::testing {

struct TestWorld {
    sim::Map map, world;
};

inline const TestWorld& test_world() {
    static const TestWorld w = [] {
        sim::ProceduralMapOptions o;
        o.style = sim::TerrainStyle::Forest;
        o.seed = 11;
        o.width_m = o.height_m = 800;
        o.year = 2008;
        TestWorld t;
        t.map = sim::generate_procedural_map(o);
        o.year = 2010;
        t.world = sim::generate_procedural_map(o);
        return t;
    }();
    return w;
}

inline sim::FlightConfig short_flight(double seconds, std::uint64_t seed = 5) {
    sim::FlightConfig c;
    c.scenario = sim::find_scenario("FR-200");
    c.frames = static_cast<std::size_t>(seconds * c.scenario.fps);
    c.seed = seed;
    return c;
}

}  // namespace trn::filter::testing
