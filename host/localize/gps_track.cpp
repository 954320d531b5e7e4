#include "trn/localize/gps_track.hpp"

#include <cstdio>
#include <filesystem>
#include <unordered_map>

#include "trn/error.hpp"
#include "trn/io/outside_text.hpp"
#include "trn/field_error.hpp"
#include "trn/sim/air_format.hpp"

namespace trn::localize {

GpsTrack read_gps_track(const std::string& folder) {
    GpsTrack t;
    if (std::filesystem::exists(folder + "/flight.json"))
        t.camera_gps = sim::read_flight_info(folder + "/flight.json").latlon_source == sim::kLatLonCameraGps;
    sim::AirReader reader(folder);
    sim::AirRecord r;
    while (reader.next(r)) {
        if (std::isfinite(r.latitude_deg) && std::isfinite(r.longitude_deg)) t.fixes.push_back({t.rows, r.filename, r.latitude_deg, r.longitude_deg});
        ++t.rows;
    }
    return t;
}

std::array<double, 2> gps_start(const GpsTrack& track, const std::string& folder,
                                const std::function<std::array<double, 2>(double, double)>& to_map_pixel) {
    if (!to_map_pixel)
        throw FieldError("start_from_gps", "the map has no georeference (a GeoTIFF, or flight.json's origin: import-photos `map_origin`), "
                                           "so a GPS fix cannot be placed on it; give `start_x, start_y` in map pixels instead");
    if (track.fixes.empty() || track.fixes.front().row != 0)
        throw FieldError("start_from_gps", folder + "/metadata.csv: the first row has no GPS fix (empty Latitude,Longitude)" +
                                               (track.fixes.empty() ? std::string(" and no row has one")
                                                                    : "; the first fix is on row " + std::to_string(track.fixes.front().row + 1) +
                                                                          " (" + track.fixes.front().filename + ")"));
    const GpsFixRow& f = track.fixes.front();
    return to_map_pixel(f.latitude_deg, f.longitude_deg);
}

GpsComparison compare_with_gps(const LocalizationResult& result, const GpsTrack& track,
                               const std::function<std::array<double, 2>(double, double)>& to_map_pixel, double mpp) {
    GpsComparison c;
    std::unordered_map<std::size_t, const GpsFixRow*> by_row;
    for (const GpsFixRow& f : track.fixes) by_row[f.row] = &f;
    c.csv = "frame,filename,gps_lat,gps_lon,gps_x,gps_y,estimate_x,estimate_y,estimate_to_gps_m\n";
    double sum = 0;
    char line[320];
    for (const LocalizationRow& row : result.rows) {
        const auto it = by_row.find(row.frame);
        if (it == by_row.end() || !to_map_pixel) {
            c.distance_m.push_back(NAN), c.fix_px.push_back({NAN, NAN});
            continue;
        }
        const GpsFixRow& f = *it->second;
        const std::array<double, 2> p = to_map_pixel(f.latitude_deg, f.longitude_deg);
        const double d = std::hypot(row.estimate_x - p[0], row.estimate_y - p[1]) * mpp;
        c.distance_m.push_back(d), c.fix_px.push_back(p);
        sum += d, ++c.compared;
        c.final_m = d;
        c.max_m = std::isnan(c.max_m) ? d : std::max(c.max_m, d);
        std::string name = io::utf8_replaced(f.filename);  // outside text (trn/io/outside_text.hpp); quoted as CSV when it must be
        if (name.find_first_of(",\"\n\r") != std::string::npos) {
            std::string q = "\"";
            for (char ch : name) q += ch == '"' ? std::string("\"\"") : std::string(1, ch);
            name = q + "\"";
        }
        std::snprintf(line, sizeof line, ",%.8f,%.8f,%.2f,%.2f,%.2f,%.2f,%.2f\n", f.latitude_deg, f.longitude_deg, p[0], p[1], row.estimate_x,
                      row.estimate_y, d);
        c.csv += std::to_string(row.frame) + "," + name + line;
    }
    if (c.compared) c.mean_m = sum / c.compared;
    return c;
}

}  // namespace trn::localize
