#pragma once
// What localizing an AIR folder needs besides the frames, from its flight.json and / or the
// caller's options: the camera's field of view, the frame rate, the map and its resolution, and
// (when the map is georeferenced) latitude / longitude of map pixels. flight.json is optional: a
// real AIR folder comes without it, and then `map`, the resolution (`metres_per_pixel`, or a
// GeoTIFF map) and the camera (`hfov_deg`, or `focal_px` with `focal_width`) are required. Options
// given beside a flight.json override it, and every override is listed in `notes`.
#include <array>
#include <functional>
#include <string>
#include <vector>

#include "trn/sim/camera.hpp"
#include "trn/sim/map.hpp"
#include "trn/export.hpp"

TRN_API_BEGIN
namespace trn::localize {

// Errors are trn::FieldError naming these fields (a front end maps them to its own spelling).
struct AirInputOptions {
    std::string dataset, map;  // the AIR folder; the map image (default: the one flight.json names)
    double metres_per_pixel = 0;  // 0: not given
    double hfov_deg = 0;       // 0: not given
    double focal_px = 0;       // 0: not given; focal length in pixels of a frame focal_width px wide
    int focal_width = 0;
    double fps = 0;            // 0: not given
    int nodata = -1;           // -1: not given; 0..255: map pixels whose every colour equals it are no-data
};

struct AirInputs {
    bool has_flight_json = false;
    std::string scenario;
    sim::Camera camera;        // hfov_deg; its size, when flight.json states it, is the one every frame must be a resized view of
    double fps = 0;            // 0: unknown (every row is a filter step)
    std::string map_path;
    sim::Map map;
    std::string latlon_source; // flight.json's (sim::FlightInfo::latlon_source): "camera_gps" for photos
    std::string georeference;  // how lat/lon are computed ("" when the map has none)
    std::function<sim::LatLon(double x, double y)> to_latlon;                   // empty without georeference
    std::function<std::array<double, 2>(double lat, double lon)> to_map_pixel;  // empty without georeference
    struct Note {
        std::string field, text;  // "field text": an option overriding flight.json, or the GeoTIFF overriding it
    };
    std::vector<Note> notes;
};

// Validates everything and loads the map; throws trn::FieldError naming the option, or trn::Error
// naming the file.
AirInputs resolve_air_inputs(const AirInputOptions& options);

}  // namespace trn::localize
TRN_API_END
