#pragma once
// Putting frame markers on the power trace's clock: the same clock, an explicit offset, or an
// automatic estimate of offset and linear drift that cross-correlates the trace with the
// markers' busy/idle pattern (sync bursts + frames busy, the rest idle).
//
// The automatic estimate maximises the contrast "mean power while busy - mean power while idle"
// over candidate offsets (coarse grid over the whole feasible range, then finer grids), then
// refines offset and drift jointly on the whole run (every edge counts, no window boundaries to
// bias it). Confidence: the strongest alternative offset at least half a frame period away
// (a slip by one frame is the classic failure), how well the sync pattern alone separates the
// two, and the scatter of per-window offsets about the fitted line. An estimate the data cannot
// tell from its alternative is marked ambiguous (integrate_run refuses it unless insisted on).
#include <string>
#include <vector>

#include "trn/energy/integrate.hpp"
#include "trn/energy/markers.hpp"
#include "trn/energy/trace.hpp"
#include "trn/export.hpp"

TRN_API_BEGIN
namespace trn::energy {

struct AlignOptions {
    bool realtime = true;     // which marker clock is read
    double guess_s = 0;       // centre of the offset search
    double search_s = 0;      // half-width of the search; 0: every offset that keeps the run inside the trace
    int windows = 4;          // windows for the drift fit (fewer when the run has few frames)
};

// Ambiguous when the alternative fits at least this well (contrast ratio) and the sync pattern,
// if any, does not separate the two by more than this ratio either.
inline constexpr double kAmbiguousRatio = 0.9;

struct Alignment {
    ClockMapping mapping;
    double residual_s = 0;   // RMS of window offsets about the fitted line
    double contrast_w = 0;   // busy minus idle mean power at the chosen mapping
    double step_s = 0;       // finest search step
    std::vector<double> window_time_s, window_offset_s;  // per window: marker time (centre) and its best offset
    // Confidence.
    double second_offset_s = 0;    // best alternative offset >= half a frame period away (at ref_s, like mapping.offset_s)
    double second_contrast_w = 0;  // its contrast (0: no alternative inside the search range)
    double candidate_ratio = 0;    // second_contrast_w / contrast_w: near 1, the data hardly prefer the estimate
    bool has_sync = false;         // the markers carry a sync pattern
    double sync_contrast_w = 0;    // busy-idle contrast of the sync pattern alone at the estimate
    double sync_ratio = 0;         // the same at the alternative / at the estimate
    bool ambiguous = false;
    std::string confidence;        // one line with the figures above and the verdict
};

// Throws trn::Error when the trace cannot hold the marker run at any offset in the search range
// or when the markers have no busy interval. An ambiguous estimate is returned, marked.
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
TRN_API_END
