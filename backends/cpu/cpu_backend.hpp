#pragma once
#include <memory>

#include "trn/backend.hpp"
#include "trn/backend_options.hpp"

namespace trn {
// The optimized CPU path: a thread pool over particles/rows, AVX2 (run-time choice) or branch-free
// vectorizable inner loops. Throws trn::Error naming the option when `options` is out of range.
std::unique_ptr<Backend> make_cpu_backend(const BackendOptions::Cpu& options);
}  // namespace trn
