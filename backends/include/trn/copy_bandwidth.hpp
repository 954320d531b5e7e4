#pragma once
// The memory-bandwidth limit that a device's Sobel and scoring are measured against (bench/, the
// device kit): STREAM's copy on the device itself. Devices with their own memory (OpenCL, Vulkan)
// measure it; the cpu backends work in host memory, whose limit is the host STREAM benchmark.
#include <cstddef>
#include <string>

#include "trn/backend.hpp"
#include "trn/export.hpp"

TRN_API_BEGIN
namespace trn {

struct CopyBandwidth {
    std::size_t bytes = 0;        // size of one buffer
    int repetitions = 0;          // timed copies (after one untimed warm-up)
    double best_seconds = 0;      // fastest copy, as STREAM reports
    double median_seconds = 0;
    double bytes_per_second = 0;  // 2 * bytes / best_seconds (read + written)
    std::string method;           // e.g. "clEnqueueCopyBuffer, profiling events"
};

// Whether measure_copy_bandwidth works on this backend (OpenCL and Vulkan devices).
bool can_measure_copy_bandwidth(const Backend& backend);

// Copies a `bytes` buffer (16 B .. 4 GiB, a multiple of 16) into another on the device
// `repetitions` times (1..1000), each timed by the device's clock. Throws trn::Error on a backend
// that cannot (naming it) and on arguments out of range.
CopyBandwidth measure_copy_bandwidth(Backend& backend, std::size_t bytes, int repetitions);

}  // namespace trn
TRN_API_END
