#pragma once
// The frame of work `trnkit frames` and `trnkit energy bench` time and measure: Sobel on a
// synthetic textured image (480p/720p/1080p), or NCC scoring of N poses of a 64x64 template on a
// 1024x1024 map (map uploaded once, here, before any frame).
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "trn/backend.hpp"
#include "trn/energy/frame_runner.hpp"

namespace trn::cli {

struct FrameWorkload {
    energy::FrameKernel kernel;               // owns its buffers; uses the backend by reference
    std::map<std::string, std::string> meta;  // backend, device, kernel, size | particles
};

// The Sobel sizes make_frame_workload knows, for the CLI checks of --size (refused at parse time).
inline const std::vector<std::string> kFrameSizeNames = {"480p", "720p", "1080p"};

// Throws trn::Error naming --size or --kernel when they are not known.
FrameWorkload make_frame_workload(Backend& backend, const std::string& kernel, const std::string& size, int particles);

}  // namespace trn::cli
