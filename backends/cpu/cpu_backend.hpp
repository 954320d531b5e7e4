#pragma once
#include <memory>

#include "trn/backend.hpp"

namespace trn {
// The optimized CPU path: a thread pool over particles/rows, AVX2 (run-time choice) or branch-free
// vectorizable inner loops.
std::unique_ptr<Backend> make_cpu_backend();
}  // namespace trn
