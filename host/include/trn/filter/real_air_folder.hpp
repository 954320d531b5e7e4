#pragma once
// An AIR flight folder (metadata.csv + flight.json + frames) from real frames and their found
// poses: the truth columns are the poses, the odometry and the magnetometer are simulated on top
// of them with the simulator's own sensor models, so a filter can be run on real imagery.
#include <string>
#include <vector>

#include "trn/export.hpp"
#include "trn/filter/frame_registration.hpp"
#include "trn/sim/sensors.hpp"

TRN_API_BEGIN
namespace trn::reg {

struct RealAirOptions {
    double metres_per_pixel = 0.5;  // the orthophoto's ground resolution (shared/data/README.md: ~0.5 m)
    double hfov_deg = 60;           // assumed; only turns the found scale into an altitude
    double fps = 0.5;               // assumed: ~25 m between frames at ~12 m/s
    sim::OdometryConfig odometry;
    sim::MagnetometerConfig magnetometer;
};

// frames[k] belongs to rows[k]. Frames are written as they are, each at its own size: the
// localizer scales every frame by its own width (flight.json's camera is the first frame's size).
// Validates everything before writing anything.
void write_real_air_folder(const std::string& folder, const std::vector<PoseRow>& rows, const std::vector<GrayImage>& frames,
                           const RealAirOptions& options);

}  // namespace trn::reg
TRN_API_END
