#pragma once
// Particle poses as CSV: columns x,y,yaw,scale (yaw in radians), an optional header line, '#'
// comments. Errors name the file and line.
#include <cstdint>
#include <iosfwd>
#include <string>
#include <vector>

#include "trn/limits.hpp"
#include "trn/scoring.hpp"
#include "trn/export.hpp"

TRN_API_BEGIN
namespace trn {

// More than max_poses poses is an error naming the line where the file passes the limit.
std::vector<Pose> read_poses_csv(std::istream& in, const std::string& source_name,
                                 std::int64_t max_poses = limits::kMaxParticles);
std::vector<Pose> read_poses_csv(const std::string& path);

}  // namespace trn
TRN_API_END
