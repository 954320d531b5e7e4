#pragma once
#include <memory>

#include "trn/backend.hpp"

namespace trn {
// The optimized CPU path: OpenMP threads over particles, branch-free vectorizable inner loops.
std::unique_ptr<Backend> make_cpu_backend();
}  // namespace trn
