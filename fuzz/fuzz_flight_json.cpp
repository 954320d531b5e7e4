// Fuzz entry: flight.json (host/sim/air_format.cpp, read_flight_info). The reader takes a path, so
// each input goes through a per-process temporary file. A refusal must be trn::Error; what it
// accepts must have metres_per_pixel > 0 (or 0: left out) and a valid camera, and write_flight_info ->
// read_flight_info must give the same description back.
#include <filesystem>
#include <fstream>
#include <unistd.h>

#include "fuzz_check.hpp"
#include "trn/error.hpp"
#include "trn/sim/air_format.hpp"

namespace {

std::string temp_path(const char* what) {
    return (std::filesystem::temp_directory_path() / ("trn-fuzz-flight-" + std::to_string(::getpid()) + what)).string();
}

bool same(const trn::sim::FlightInfo& a, const trn::sim::FlightInfo& b) {
    const bool origin = a.origin.has_value() == b.origin.has_value() &&
                        (!a.origin || (a.origin->latitude_deg == b.origin->latitude_deg && a.origin->longitude_deg == b.origin->longitude_deg));
    return origin && a.scenario == b.scenario && a.map_file == b.map_file && a.metres_per_pixel == b.metres_per_pixel &&
           a.camera.width == b.camera.width && a.camera.height == b.camera.height && a.camera.hfov_deg == b.camera.hfov_deg &&
           a.fps == b.fps && a.map_year == b.map_year && a.rendered_year == b.rendered_year && a.seed == b.seed &&
           a.latlon_source == b.latlon_source;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    using trn::fuzz::require;
    static const std::string input = temp_path(".json"), copy = temp_path("-copy.json");
    std::ofstream(input, std::ios::binary | std::ios::trunc).write(reinterpret_cast<const char*>(data), static_cast<std::streamsize>(size));
    trn::sim::FlightInfo info;
    try {
        info = trn::sim::read_flight_info(input);
    } catch (const trn::Error&) {
        return 0;
    }
    require(info.metres_per_pixel >= 0, "metres_per_pixel < 0 accepted");  // 0: left out (no map, or a GeoTIFF's own)
    info.camera.validate();  // throws (and so fails) if an invalid camera was accepted
    trn::sim::write_flight_info(copy, info);
    trn::sim::FlightInfo back;
    try {
        back = trn::sim::read_flight_info(copy);
    } catch (const trn::Error& e) {
        std::fprintf(stderr, "%s\n", e.what());
        trn::fuzz::violation("flight.json written from an accepted one is refused");
    }
    require(same(info, back), "write -> read changed the flight description");
    return 0;
}
