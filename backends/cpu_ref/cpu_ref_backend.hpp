#pragma once
#include <memory>

#include "trn/backend.hpp"

namespace trn {
// The naive oracle: straight loops, double accumulation, two-pass statistics.
std::unique_ptr<Backend> make_cpu_ref_backend();
}  // namespace trn
