#pragma once
// Picks the fastest usable backend for particle scoring on this machine by timing one realistic
// batch (a 160x120 template, 1000 particles) on each available device, after a warm-up call.
#include <memory>
#include <string>
#include <vector>

#include "trn/backend.hpp"

namespace trn::filter {

struct BackendTiming {
    std::string name;
    double score_ms = 0;  // one batch, after warm-up
};

// Times every available backend except cpu-ref (the slow oracle) unless it is the only one; the
// fastest comes back created, the timings of all in `timings`.
std::unique_ptr<Backend> create_fastest_backend(std::vector<BackendTiming>* timings = nullptr);

}  // namespace trn::filter
