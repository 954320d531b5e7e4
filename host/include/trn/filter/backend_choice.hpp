#pragma once
// `--backend fastest` with timings: picks the scoring backend by the registry's fixed preference
// order (BackendRegistry::preferred_order), so that two runs on the same machine always score on
// the same backend. Every candidate is still timed on one realistic batch (a 160x120 template,
// 1000 particles, after a warm-up) for the printout; a candidate that fails that batch is skipped.
#include <memory>
#include <string>
#include <vector>

#include "trn/backend.hpp"
#include "trn/backend_options.hpp"
#include "trn/export.hpp"

TRN_API_BEGIN
namespace trn::filter {

struct BackendTiming {
    std::string name;
    double score_ms = 0;  // one batch, after warm-up
};

// Creates the first usable backend in preference order with `options`; the timings of all usable
// candidates in `timings`. Throws BackendUnavailable when none is usable.
std::unique_ptr<Backend> create_fastest_backend(const BackendOptions& options, std::vector<BackendTiming>* timings = nullptr);

}  // namespace trn::filter
TRN_API_END
