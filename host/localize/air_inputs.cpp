#include "trn/localize/air_inputs.hpp"

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <memory>

#include "trn/error.hpp"
#include "trn/field_error.hpp"
#include "trn/io/geotiff.hpp"
#include "trn/sim/air_format.hpp"
#include "trn/detail/angles.hpp"
#include "trn/sim/geodesy.hpp"

namespace trn::localize {
namespace {

constexpr double kDegPerRad = 180.0 / kPi;  // degrees per radian (trn::kDeg is radians per degree)

std::string number(double v) {
    char buf[40];
    std::snprintf(buf, sizeof buf, "%.8g", v);
    return buf;
}

// Inverse of sim::map_pixel_to_latlon (flight.json's origin, local equirectangular projection).
std::array<double, 2> origin_latlon_to_pixel(const sim::GeoOrigin& o, double mpp, double lat, double lon) {
    const auto [east, south] = sim::latlon_to_local_m(o, lat, lon);
    return {east / mpp, south / mpp};
}

// The horizontal field of view the options give (0: none). A focal length is in pixels of a frame
// of a stated width, so frames of any width get their own focal length from it.
double option_hfov(const AirInputOptions& o) {
    if (o.hfov_deg > 0 && o.focal_px > 0) throw FieldError("hfov_deg", "give `hfov_deg` or `focal_px`, not both");
    if ((o.focal_px > 0) != (o.focal_width > 0))
        throw FieldError("focal_px", "`focal_px` and `focal_width` go together: the focal length in pixels of frames that many pixels wide");
    if (o.focal_px > 0) return 2 * std::atan(0.5 * o.focal_width / o.focal_px) * kDegPerRad;
    return o.hfov_deg;
}

}  // namespace

AirInputs resolve_air_inputs(const AirInputOptions& o) {
    namespace fs = std::filesystem;
    if (!fs::is_directory(o.dataset)) throw FieldError("dataset", o.dataset + ": not a folder");
    AirInputs in;
    const std::string info_path = o.dataset + "/flight.json";
    in.has_flight_json = fs::exists(info_path);
    const double hfov = option_hfov(o);
    const bool geotiff = !o.map.empty() && io::has_geotiff_extension(o.map);

    sim::FlightInfo info;
    if (in.has_flight_json) {
        info = sim::read_flight_info(info_path);
        in.scenario = info.scenario;
        in.camera = info.camera;
        in.fps = info.fps;
        in.latlon_source = info.latlon_source;
        if (!o.map.empty() && !info.map_file.empty()) in.notes.push_back({"map", o.map + " overrides flight.json's map_file " + info.map_file});
        if (!(info.metres_per_pixel > 0) && !(o.metres_per_pixel > 0) && !geotiff)  // a folder that names no map (import-photos)
            throw FieldError("metres_per_pixel", "required: " + info_path + " names no map resolution and the map is not a GeoTIFF");
        if (o.metres_per_pixel > 0 && info.metres_per_pixel > 0 && o.metres_per_pixel != info.metres_per_pixel)
            in.notes.push_back({"metres_per_pixel", number(o.metres_per_pixel) + " overrides flight.json's metres_per_pixel " + number(info.metres_per_pixel)});
        if (hfov > 0 && std::fabs(hfov - info.camera.hfov_deg) > 1e-9)
            in.notes.push_back({o.focal_px > 0 ? "focal_px" : "hfov_deg",
                                (o.focal_px > 0 ? "and `focal_width` (hfov " + number(hfov) + " deg)" : number(hfov)) +
                                    " overrides flight.json's camera.hfov_deg " + number(info.camera.hfov_deg)});
        if (o.fps > 0 && o.fps != info.fps) in.notes.push_back({"fps", number(o.fps) + " overrides flight.json's fps " + number(info.fps)});
        in.map_path = !o.map.empty() ? o.map : info.map_file.empty() ? "" : o.dataset + "/" + info.map_file;
        if (in.map_path.empty()) throw FieldError("map", "flight.json names no map; give `map` FILE");
    } else {
        // A real AIR folder: everything flight.json would say must come from the options.
        const std::string why = "required: " + info_path + " is absent (a real AIR folder)";
        if (o.map.empty()) throw FieldError("map", why);
        if (!(o.metres_per_pixel > 0) && !geotiff) throw FieldError("metres_per_pixel", why + " and the map is not a GeoTIFF");
        if (!(hfov > 0)) throw FieldError("hfov_deg (or focal_px with focal_width)", why);
        in.scenario = "AIR folder " + o.dataset;
        in.camera = {640, 480, 60};  // placeholder size: each frame's own size is used
        in.map_path = o.map;
    }
    if (hfov > 0) in.camera.hfov_deg = hfov;
    if (o.fps > 0) in.fps = o.fps;
    in.camera.validate();

    if (o.nodata < -1 || o.nodata > 255) throw FieldError("nodata", "must be a grey level 0..255, got " + std::to_string(o.nodata));
    const std::optional<int> nodata = o.nodata >= 0 ? std::optional<int>(o.nodata) : std::nullopt;
    if (geotiff) {
        io::GeoTiff g = io::read_geotiff(in.map_path, nodata);
        if (o.metres_per_pixel > 0 && std::fabs(o.metres_per_pixel - g.metres_per_pixel) > 1e-6 * g.metres_per_pixel)
            throw FieldError("metres_per_pixel", number(o.metres_per_pixel) + " contradicts " + in.map_path + ", whose geotransform gives " +
                                                     number(g.metres_per_pixel) + " m/px; leave `metres_per_pixel` out");
        if (in.has_flight_json && info.metres_per_pixel > 0 && std::fabs(info.metres_per_pixel - g.metres_per_pixel) > 1e-6 * g.metres_per_pixel)
            in.notes.push_back({"", in.map_path + "'s geotransform (" + number(g.metres_per_pixel) + " m/px) overrides flight.json's metres_per_pixel " +
                                        number(info.metres_per_pixel)});
        auto geo = std::make_shared<io::GeoReference>(g, in.map_path);
        in.georeference = "GeoTIFF CRS " + g.crs_name + " (GDAL/PROJ)";
        in.to_latlon = [geo](double x, double y) {
            const io::GeoPoint p = geo->to_latlon(x, y);
            return sim::LatLon{p.latitude_deg, p.longitude_deg};
        };
        in.to_map_pixel = [geo](double lat, double lon) { return geo->to_pixel(lat, lon); };
        in.map.metres_per_pixel = g.metres_per_pixel;
        in.map.image = std::move(g.image);
        in.map.valid = std::move(g.valid);
    } else {
        in.map = sim::load_map(in.map_path, o.metres_per_pixel > 0 ? o.metres_per_pixel : info.metres_per_pixel, info.origin, nodata);
        if (info.origin) {
            sim::Map frame;  // resolution and origin only: the lambdas outlive no image
            frame.metres_per_pixel = in.map.metres_per_pixel, frame.origin = info.origin;
            const sim::GeoOrigin origin = *info.origin;
            const double mpp = in.map.metres_per_pixel;
            in.georeference = "flight.json origin (local equirectangular projection)";
            in.to_latlon = [frame](double x, double y) { return sim::map_pixel_to_latlon(frame, x, y); };
            in.to_map_pixel = [origin, mpp](double lat, double lon) { return origin_latlon_to_pixel(origin, mpp, lat, lon); };
        }
    }
    return in;
}

}  // namespace trn::localize
