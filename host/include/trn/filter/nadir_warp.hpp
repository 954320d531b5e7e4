#pragma once
// Tilt compensation of a camera fixed to the body (no gimbal): a frame taken with roll / pitch is
// warped to what a level camera at the same place would have seen, so it is scored at the right
// place and scale. The warp is the pure-rotation homography K R K^-1 (independent of position,
// heading and altitude; same conventions as sim::camera_to_map_homography, which renders such
// frames). The result is cropped to the centred rectangle the tilted frame covers completely,
// so no fill pixels enter the NCC; its centre is still the point below the camera.
#include <string>

#include "trn/io/image_io.hpp"
#include "trn/export.hpp"

TRN_API_BEGIN
namespace trn::filter {

// Largest tilt (angle of the optical axis from the vertical) a frame may have and still be scored:
// 10 degrees. The level view must stay centred on the point below the camera (the scorer's pose is
// the template centre), so the crop shrinks fast with tilt: for a 60-degree 4:3 lens it keeps 55-63 %
// of the width (30-40 % of the ground) at 10 degrees, 34-46 % (12-21 %) at 15 and 14-30 % at 20
// (pitch-roll; tests/filter/test_nadir_warp.cpp prints them). At 10 degrees a 455 px real frame
// still gives a 250 px crop, more than the 160 px template, so the scored template loses no detail.
inline constexpr double kDefaultMaxTiltDeg = 10;

struct NadirFrame {
    GrayImage image;          // level view, cropped; same pixel size as the input (one focal length)
    double kept_fraction = 1; // crop width / frame width
};

// hfov_deg: horizontal field of view of `frame` (its own width). Throws trn::Error when the tilt is
// so large that no centred crop of at least 8 px survives.
NadirFrame warp_to_nadir(GrayView frame, double hfov_deg, double roll_rad, double pitch_rad);

// Tilt of the optical axis from the vertical, degrees, for a measured roll and pitch (radians).
double tilt_deg(double roll_rad, double pitch_rad);

// Below this tilt (degrees) a frame is level and scored as it is: a quaternion written for
// roll = pitch = 0 reads back as ~1e-14 deg.
inline constexpr double kLevelTiltDeg = 1e-6;

// A frame with a measured attitude made ready for scoring, one rule for every path (the AIR flight
// source, the Localizer): too_oblique when tilted beyond max_tilt_deg or when no level view is
// left (`error` says why); else `image` is the level view, or empty when the frame is level
// already. Throws trn::Error when a tilted frame comes without a valid hfov_deg.
struct LevelledFrame {
    double tilt_deg = 0;
    bool too_oblique = false;
    GrayImage image;
    std::string error;
};
LevelledFrame level_frame(GrayView frame, double hfov_deg, double roll_rad, double pitch_rad, double max_tilt_deg);

}  // namespace trn::filter
TRN_API_END
