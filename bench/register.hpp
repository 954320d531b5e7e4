#pragma once
// Each benchmark family registers its cases for the chosen sweep and the devices present.
#include <string>

#include "sweep.hpp"

namespace trn::bench {

void register_sobel_benchmarks(const Sweep& sweep);
void register_ncc_benchmarks(const Sweep& sweep);
void register_stream_benchmarks(const Sweep& sweep);
void register_device_copy_benchmarks(const Sweep& sweep);
void register_setup_benchmarks(const Sweep& sweep);
void register_latency_benchmarks(const Sweep& sweep);  // frame to MAVLink message on a real flight

// Whether OpenCV's OpenCL path (cv::UMat) is really on, and on what: for benchmark names
// ("OpenCL_PoCL", "OpenCL_OFF") and labels ("OpenCL on Portable Computing Language: cpu-...").
std::string opencv_opencl_tag();
std::string opencv_opencl_description();

}  // namespace trn::bench
