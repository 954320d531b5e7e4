#pragma once
// What `trnkit localize` needs to know besides the frames, from flight.json and / or the command
// line: the camera's field of view, the frame rate, the map and its resolution, and (when the map
// is georeferenced) latitude / longitude of map pixels. flight.json is optional: a real AIR folder
// comes without it, and then --map, the resolution (--mpp, or a GeoTIFF map) and the camera
// (--hfov-deg, or --focal-px with --focal-width) are required. Options given beside a flight.json
// override it, and every override is listed in `notes` for stderr.
#include <array>
#include <functional>
#include <string>
#include <vector>

#include "trn/sim/camera.hpp"
#include "trn/sim/map.hpp"

namespace trn::cli {

struct LocalizeInputOptions {
    std::string dataset, map;
    double mpp = 0;            // 0: not given
    double hfov_deg = 0;       // 0: not given
    double focal_px = 0;       // 0: not given; focal length in pixels of a frame focal_width px wide
    int focal_width = 0;
    double fps = 0;            // 0: not given
};

struct LocalizeInputs {
    bool has_flight_json = false;
    std::string scenario;
    sim::Camera camera;        // only hfov_deg matters: each frame's own width gives its scale
    double fps = 0;            // 0: unknown (every row is a filter step)
    std::string map_path;
    sim::Map map;
    std::string georeference;  // how lat/lon are computed ("" when the map has none)
    std::function<sim::LatLon(double x, double y)> to_latlon;                   // empty without georeference
    std::function<std::array<double, 2>(double lat, double lon)> to_map_pixel;  // empty without georeference
    std::vector<std::string> notes;                                            // options that override flight.json
};

// Validates everything and loads the map; throws trn::Error naming the option or file.
LocalizeInputs resolve_localize_inputs(const LocalizeInputOptions& options);

}  // namespace trn::cli
