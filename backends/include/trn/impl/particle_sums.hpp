#pragma once
// For backend implementers only (the backends in this tree, or a family added to a registry):
// what an optimized backend accumulates per particle and the one host function that turns it
// into scores. Callers of Backend::score never need this header.
#include <cstdint>

#include "trn/export.hpp"
#include "trn/scoring.hpp"
#include "trn/scoring_plan.hpp"

TRN_API_BEGIN
namespace trn {

// Per-particle sums every backend accumulates over its valid samples, exactly: J = the map value I
// in 1/128 grey levels (fixed::bilinear), T = plan.quantized. int64 cannot overflow (fixed_point.hpp).
struct ParticleSums {
    std::int64_t n = 0, sj = 0, sjj = 0, sjt = 0, st = 0, stt = 0;
};

// Turns the sums into scores and flags by the rules in scoring.hpp (128-bit integer products, so
// cancellation costs nothing; the same bits for the same sums).
ParticleScore finalize_score(const ParticleSums& s, const ScoringPlan& plan);

}  // namespace trn
TRN_API_END
