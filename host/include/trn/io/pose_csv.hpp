#pragma once
// Particle poses as CSV: columns x,y,yaw,scale (yaw in radians), an optional header line, '#'
// comments. Errors name the file and line.
#include <iosfwd>
#include <string>
#include <vector>

#include "trn/scoring.hpp"

namespace trn {

std::vector<Pose> read_poses_csv(std::istream& in, const std::string& source_name);
std::vector<Pose> read_poses_csv(const std::string& path);

}  // namespace trn
