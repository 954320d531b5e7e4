#pragma once
// An AIR folder's GPS fixes as a reference track (`trnkit import-photos` keeps a camera's fixes in
// metadata.csv's Latitude/Longitude, flight.json's latlon_source "camera_gps"): the first fix as a
// start prior (`localize --start-from-gps`) and the distance of each estimate from the fix of its
// frame. A camera's GPS is not ground truth: its fix lags the photo (seconds: metres at flight
// speed) and drifts by metres, so the distance bounds nothing; it only shows a run that went wrong.
#include <array>
#include <cmath>
#include <functional>
#include <string>
#include <vector>

#include "trn/localize/localization.hpp"
#include "trn/export.hpp"

TRN_API_BEGIN
namespace trn::localize {

struct GpsFixRow {
    std::size_t row = 0;  // metadata.csv row (0 = first), as LocalizationRow::frame counts
    std::string filename;
    double latitude_deg = 0, longitude_deg = 0;
};

struct GpsTrack {
    bool camera_gps = false;        // flight.json's latlon_source is "camera_gps"
    std::size_t rows = 0;           // rows of metadata.csv
    std::vector<GpsFixRow> fixes;   // rows with Latitude/Longitude (empty cells: no fix)
};

// Reads metadata.csv's Latitude/Longitude and flight.json's latlon_source (flight.json optional).
GpsTrack read_gps_track(const std::string& folder);

// The first row's fix as a start (map pixels) through `to_map_pixel`; throws trn::FieldError
// "start_from_gps" when the first row has no fix.
std::array<double, 2> gps_start(const GpsTrack& track, const std::string& folder,
                                const std::function<std::array<double, 2>(double lat, double lon)>& to_map_pixel);

struct GpsComparison {
    std::vector<double> distance_m;  // per result row: estimate to its frame's fix, metres (NaN: no fix)
    std::vector<std::array<double, 2>> fix_px;  // per result row: the fix in map pixels (NaN: none)
    double mean_m = NAN, final_m = NAN, max_m = NAN;
    std::size_t compared = 0;
    std::string csv;                 // gps_track.csv: frame,filename,gps_lat,gps_lon,gps_x,gps_y,estimate_x,estimate_y,estimate_to_gps_m
};
GpsComparison compare_with_gps(const LocalizationResult& result, const GpsTrack& track,
                               const std::function<std::array<double, 2>(double lat, double lon)>& to_map_pixel, double metres_per_pixel);

// The caveat printed and stored with every such distance.
inline constexpr const char* kCameraGpsCaveat =
    "camera GPS is a reference, not the truth: its fix lags the photo (seconds) and drifts by metres";

}  // namespace trn::localize
TRN_API_END
