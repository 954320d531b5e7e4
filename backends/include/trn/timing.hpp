#pragma once
// Phase timing reported by backend calls (shared by every layer that measures work).
#include "trn/export.hpp"

TRN_API_BEGIN
namespace trn {

// Wall time of the three phases of one call, in milliseconds, from the backend's own clock
// (OpenCL profiling events, Vulkan timestamp queries, steady_clock on the CPU).
struct PhaseTimes {
    double upload_ms = 0;
    double execute_ms = 0;
    double download_ms = 0;
    double total_ms() const { return upload_ms + execute_ms + download_ms; }
};

}  // namespace trn
TRN_API_END
