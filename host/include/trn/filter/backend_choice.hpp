#pragma once
// `--backend fastest`: picks the scoring backend by a fixed preference order, so that two runs on
// the same machine always score on the same backend (a timing race could flip between near-equal
// devices and make results differ from run to run). Order: GPU devices (OpenCL, then Vulkan, by
// name), then the optimised CPU backend, then any other device (e.g. PoCL / lavapipe on the CPU),
// and cpu-ref (the slow oracle) only when it is the only one. Every candidate is still timed on one
// realistic batch (a 160x120 template, 1000 particles, after a warm-up) for the printout.
#include <memory>
#include <string>
#include <vector>

#include "trn/backend.hpp"

namespace trn::filter {

struct BackendTiming {
    std::string name;
    double score_ms = 0;  // one batch, after warm-up
};

// The device names in preference order (see above); pure, so the order is testable.
std::vector<std::string> preferred_backend_order(const std::vector<DeviceInfo>& devices);

// Creates the first usable backend in preference order; the timings of all usable candidates in
// `timings`. Throws BackendUnavailable when none is usable.
std::unique_ptr<Backend> create_fastest_backend(std::vector<BackendTiming>* timings = nullptr);

}  // namespace trn::filter
