#pragma once
// Putting frame markers on the power trace's clock: the same clock, an explicit offset, or an
// automatic estimate of offset and linear drift that cross-correlates the trace with the
// markers' busy/idle pattern (sync bursts + frames busy, the rest idle).
//
// The automatic estimate maximises the contrast "mean power while busy - mean power while idle"
// over candidate offsets (coarse grid over the whole feasible range, then finer grids), then
// repeats a narrow search in consecutive windows of the run and fits offset = a + drift x time
// through the window offsets. The residual is the RMS of the window offsets about that line.
#include <string>
#include <vector>

#include "trn/energy/integrate.hpp"
#include "trn/energy/markers.hpp"
#include "trn/energy/trace.hpp"

namespace trn::energy {

struct AlignOptions {
    bool realtime = true;     // which marker clock is read
    double guess_s = 0;       // centre of the offset search
    double search_s = 0;      // half-width of the search; 0: every offset that keeps the run inside the trace
    int windows = 4;          // windows for the drift fit (fewer when the run has few frames)
};

struct Alignment {
    ClockMapping mapping;
    double residual_s = 0;   // RMS of window offsets about the fitted line
    double contrast_w = 0;   // busy minus idle mean power at the chosen mapping
    double step_s = 0;       // finest search step
    std::vector<double> window_time_s, window_offset_s;  // per window: marker time (centre) and its best offset
};

// Throws trn::Error when the trace cannot hold the marker run at any offset in the search range
// or when the markers have no busy interval.
Alignment align_auto(const PowerTrace& trace, const MarkerFile& markers, const AlignOptions& options);

// How much the frame energies move when the markers shift by -dt and +dt (dt: the median sample
// period): sum |E(shifted) - E| / sum |E| over usable frames, gross energy.
struct ShiftSensitivity {
    double dt_s = 0;
    double relative_minus = 0, relative_plus = 0;
};
ShiftSensitivity shift_sensitivity(const PowerTrace& trace, const MarkerFile& markers, const ClockMapping& mapping,
                                   const IntegrationOptions& options);

}  // namespace trn::energy
