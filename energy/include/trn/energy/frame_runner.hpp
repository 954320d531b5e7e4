#pragma once
// The dissertation's Algorithm 3 as a reusable loop: run a kernel K times with idle gaps, after
// a recognisable sync pattern, and record every interval on CLOCK_MONOTONIC and CLOCK_REALTIME.
//
// Timeline: lead idle, sync bursts of 3u, 1u, 2u busy separated by u idle (unequal lengths, so
// cross-correlation cannot lock onto the wrong frame), idle, then frame/idle pairs, and a final
// idle. Every interval is a row of the marker file (markers.hpp).
#include <functional>
#include <map>
#include <string>

#include "trn/energy/markers.hpp"
#include "trn/scoring.hpp"
#include "trn/export.hpp"

TRN_API_BEGIN
namespace trn::energy {

struct FrameRunConfig {
    int frames = 100;
    double idle_s = 0.1;       // gap after every frame
    double lead_idle_s = 1.0;  // idle before the sync pattern and after the last frame (idle baseline)
    double sync_unit_s = 0.1;  // u in the sync pattern above; 0 disables the pattern
    std::map<std::string, std::string> meta;  // copied into the marker file's header
};

// One frame of work; returns its write/exec/read phase times (PhaseTimes upload/execute/download).
using FrameKernel = std::function<PhaseTimes()>;

// Runs the timeline above; throws trn::Error for a non-positive frame count or negative times.
MarkerFile run_frames(const FrameKernel& kernel, const FrameRunConfig& config);

// Nanoseconds on CLOCK_MONOTONIC and CLOCK_REALTIME, read back to back.
struct ClockPair {
    std::int64_t mono_ns = 0, real_ns = 0;
};
ClockPair now_both();

}  // namespace trn::energy
TRN_API_END
