#pragma once
// For backend implementers only (the backends in this tree, or a family added to a registry):
// what an optimized backend accumulates per particle and the one host function that turns it
// into scores. Callers of Backend::score never need this header.
#include "trn/export.hpp"
#include "trn/scoring.hpp"
#include "trn/scoring_plan.hpp"

TRN_API_BEGIN
namespace trn {

// Per-particle sums an optimized backend accumulates over its valid samples, with
// J = sampled map value - shift (shift: the map value at the pose centre, which keeps float sums
// well conditioned) and T' = plan.centered.
struct ParticleSums {
    double n = 0, sj = 0, sjj = 0, sjt = 0, st = 0, stt = 0;
    double shift = 0;
};

// Turns the sums into scores and flags by the rules in scoring.hpp.
ParticleScore finalize_score(const ParticleSums& s, const ScoringPlan& plan);

}  // namespace trn
TRN_API_END
