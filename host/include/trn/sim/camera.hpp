#pragma once
// The downward-looking pinhole camera and how a frame relates to the map.
//
// Camera pixel (u, v) with centre c = ((W-1)/2, (H-1)/2) looks at the ground point
//     (x, y) + scale * R(yaw) * (u - cx, v - cy)         (map pixels, R = [cos -sin; sin cos])
// when the gimbal holds the camera level (roll = pitch = 0), with
//     scale = altitude / (focal_px * metres_per_pixel),   focal_px = (W/2) / tan(hfov/2),
// which is exactly the pose convention of trn/scoring.hpp: a frame rendered at (x, y, yaw) scores
// at Pose{x, y, yaw, scale}. Yaw is the compass heading of the top of the frame (the direction of
// flight): 0 = north (map up), +pi/2 = east; positive yaw turns the frame clockwise on the map.
#include <array>
#include "trn/export.hpp"

TRN_API_BEGIN
namespace trn::sim {

struct Camera {
    int width = 640;
    int height = 480;
    double hfov_deg = 60.0;  // horizontal field of view

    double focal_px() const;
    void validate() const;  // throws trn::Error naming the bad field
};

// Map pixels per camera pixel at this altitude above ground (the Pose::scale of a level frame).
double template_scale(const Camera& camera, double altitude_m, double metres_per_pixel);

// Where the camera is: map pixel under the aircraft, height above ground, heading and the small
// roll / pitch that an unstabilised camera would see (0 with the gimbal).
struct CameraPose {
    double map_x = 0, map_y = 0;
    double altitude_m = 100;
    double yaw_rad = 0;
    double roll_rad = 0;   // positive: right wing down, the view shifts to the left
    double pitch_rad = 0;  // positive: nose up, the view shifts forward
};

// Row-major 3x3 homography from camera pixel (u, v, 1) to map pixel (x, y, 1) (up to scale).
// With roll = pitch = 0 it is the affine map of the header comment.
std::array<double, 9> camera_to_map_homography(const Camera& camera, const CameraPose& pose, double metres_per_pixel);

}  // namespace trn::sim
TRN_API_END
