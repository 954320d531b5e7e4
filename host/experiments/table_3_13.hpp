#pragma once
// Table 3.13 [3.7]: DPC-PFL against visual odometry on FL-200, FL-300, UL-200 and UL-300, our
// numbers (our image-based odometry as the baseline) beside the dissertation's (SVO, ORB-SLAM2).
#include <functional>
#include <string>

namespace trn::experiments {

// mean(preset, key): the mean of a job-result key over that preset's finished jobs (NaN: none).
// Writes table_3_13.md / .csv into `out`; returns the Markdown.
std::string table_3_13(const std::function<double(const std::string& preset, const char* key)>& mean, const std::string& out);

}  // namespace trn::experiments
