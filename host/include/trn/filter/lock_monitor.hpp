#pragma once
// Notices a confident lock on the wrong place. Two kinds of evidence, per filter step:
//   - contrast: the best particle's NCC against what random places score. A few probe poses at
//     random places in a ring around the estimate are scored with the particles (same batch);
//     contrast = (best NCC - probes' mean) / probes' sd. A true lock stands out; a wrong one is
//     one more local maximum of similar texture. Weak = contrast below `min_contrast`.
//   - odometry consistency: the estimate against dead reckoning (odometry increments) from the
//     last fix (the start counts as a fix within the initialisation radius); leaving the
//     odometry's plausible drift (`drift_fraction` of the distance since, plus `drift_floor_m`,
//     plus the fix's own uncertainty) is inconsistent. While the cloud is still spread (rms above
//     `converged_m`) neither a fix nor an inconsistency is declared: its mean means little.
// A fix restarts dead reckoning at the estimate and forgets the start's uncertainty, which cannot
// be undone (every later widening searches around it), so it needs more than one good step:
//   - the contrast must reach `confident_contrast` plus `fix_far_contrast` per drift bound of
//     distance from dead reckoning. Why: a place far from dead reckoning is a priori less likely,
//     and the farther the filter may look, the more places compete and the higher the best of the
//     wrong ones scores (look-elsewhere). Wrong places ~250 m from the start of a 300 m prior
//     reached 5.1-7.9 (FL-200, UL-200-wind and FC-300-wind seed 1), true locks average 10-12
//     (docs/RESULTS.md); so a fix at the drift bound needs twice the contrast of one at dead
//     reckoning (the wrong places above would need ~9.6);
//   - and that for `fix_steps` consecutive steps on one track (each estimate within `converged_m`
//     of the previous one moved by the odometry): one lucky frame is not a place.
// A candidate still being confirmed is not declared lost (its evidence is strong, not weak).
// Lost = inconsistent without being a candidate fix, or weak for `weak_steps` steps in a row.
// When lost, the filter re-scatters `widen_fraction` of its particles around the dead-reckoned
// position, within the drift bound (at most `widen_radius_m`); the rest keep the current
// hypothesis, which wins again at once if it was right. The monitor then waits `cooldown_steps`
// before its next verdict. Every event is counted.
// Small maps (issue 43): when fewer than kMinProbes of the ring's probes scored (the ring lies off a
// map a few hundred metres wide, or on its no-data), the filter scores a second set, "near probes":
// random places inside the map, at least one frame footprint away from the estimate (so no probe
// overlaps the place being judged), drawn from their own random stream so that wherever the ring
// works every draw and verdict stays as it was.
// The search is widened no further than the drift bound on purpose: over weak texture the true
// lock itself has a low contrast, and a wider disc always holds some other place that scores
// better than the truth (a version that doubled the radius at every loss walked off correct
// FR-200 / FR-300 locks over a bare field). So a wrong lock is escaped when the truth lies within
// what the odometry allows since the last fix (e.g. within the initialisation radius of the start).
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

#include "trn/scoring.hpp"
#include "trn/export.hpp"

TRN_API_BEGIN
namespace trn::filter {

struct LockMonitorConfig {
    bool enabled = true;
    std::size_t probes = 48;            // random places scored per step (0: no contrast evidence)
    double probe_min_m = 150, probe_max_m = 600;  // ring around the estimate where probes go
    double min_contrast = 3.0;          // best NCC must exceed the probes' mean by this many sd
    double confident_contrast = 5.5;    // a step this distinct is a fix: dead reckoning restarts there
    double converged_m = 30;            // ... if the particle cloud is within this rms radius
    double fix_far_contrast = 5.5;      // ... plus this much per drift bound of distance from dead reckoning
    std::size_t fix_steps = 3;          // ... held for this many consecutive steps on one track
    std::size_t weak_steps = 8;         // consecutive weak steps that make "lost"
    double drift_fraction = 0.15;       // allowed departure from dead reckoning per metre flown
    double drift_floor_m = 40;          // ... plus this
    double widen_fraction = 0.5;        // share of the particles re-scattered when lost
    double widen_radius_m = 300;        // most radius of the wider search around dead reckoning
    std::size_t cooldown_steps = 10;    // steps after a widening without a verdict

    void validate() const;  // throws trn::Error naming the field and its range
};

struct LockReport {
    double best_ncc = NAN, probe_mean = NAN, probe_sd = NAN, contrast = NAN;
    double drift_m = NAN, drift_bound_m = NAN;  // |estimate - dead reckoning| and its bound
    double fix_contrast = NAN;  // the contrast a fix at this distance from dead reckoning needs
    std::size_t fix_run = 0;    // consecutive steps that met it on one track (a fix at fix_steps)
    bool weak = false, confident = false, inconsistent = false, lost = false;  // confident: a fix
    bool fixed_before = false;  // a fix since the start, the last loss or the last weak step: the position was judged
    bool redrawn = false;       // set by the filter: the step re-initialised (every weight collapsed)
    bool blind = false;         // set by the filter: no particle had a valid score (the frame told nothing)
    double widen_radius_m = 0;  // when lost: re-scatter within this radius of dead reckoning
};

class LockMonitor {
public:
    LockMonitor(const LockMonitorConfig& config, double metres_per_pixel, std::uint64_t seed);

    // A new start: dead reckoning from (x, y) map pixels, known to within `uncertainty_m`.
    void reset(double x, double y, double uncertainty_m);
    // This step's odometry increment, map pixels (x east, y south).
    void predict(double dx_px, double dy_px);
    // Appends the probe poses for this step around (x, y) at `yaw`; returns how many.
    std::size_t add_probes(double x, double y, double yaw, std::vector<Pose>& poses);
    // Fewer valid probe scores than this: no contrast evidence (assess) / the near probes (above).
    static constexpr std::size_t kMinProbes = 8;
    // Appends up to config.probes near probes: inside a map_width x map_height pixel map, at least
    // `footprint_px` (the frame's width on the map) and at most probe_max_m from (x, y). Returns how
    // many (0 when the map holds no such place).
    std::size_t add_near_probes(double x, double y, double yaw, double footprint_px, int map_width, int map_height, std::vector<Pose>& poses);
    // The verdict from the best particle's NCC, the probes' scores, the estimate (map pixels) and
    // the particle cloud's rms spread around it (metres).
    LockReport assess(double best_ncc, std::span<const ParticleScore> probe_scores, double estimate_x, double estimate_y,
                      double spread_m);

    double dead_reckoning_x() const { return dead_x_; }
    double dead_reckoning_y() const { return dead_y_; }
    const LockMonitorConfig& config() const { return config_; }

private:
    double uniform();

    LockMonitorConfig config_;
    double mpp_;
    std::uint64_t rng_;
    std::uint64_t near_rng_;  // the near probes' own stream
    double dead_x_ = 0, dead_y_ = 0, since_fix_m_ = 0, fix_uncertainty_m_ = 0;
    double candidate_x_ = 0, candidate_y_ = 0;  // last step of the current fix candidate, moved by odometry
    std::size_t weak_run_ = 0, cooldown_ = 0, candidate_run_ = 0;
    bool fixed_ = false;  // a fix since the start, the last loss or the last weak step
};

}  // namespace trn::filter
TRN_API_END
