#pragma once
// What the C API's opaque handles hold. A map keeps a reference to its backend, so C callers may
// destroy the two in either order.
#include <memory>
#include <string>
#include <vector>

#include "trn/backend.hpp"
#include "trn/energy/run_report.hpp"
#include "trn/scoring_plan.hpp"
#include "trn/trnkit.h"

struct trn_device_list {
    std::vector<trn::DeviceInfo> devices;
};

struct trn_backend {
    std::shared_ptr<trn::Backend> impl;
};

struct trn_map {
    std::shared_ptr<trn::Backend> backend;  // declared first: the map is released before its backend
    trn::MapHandle handle;
};

struct trn_plan {
    trn::ScoringPlan plan;
};

struct trn_energy_result {
    trn::energy::RunReport report;
};

namespace trn::capi {

// Fills a C view of a DeviceInfo whose strings live as long as `info`.
inline trn_device_info c_device_info(const DeviceInfo& info) {
    return {info.name.c_str(), info.family.c_str(), info.device.c_str(), info.type.c_str(), info.driver.c_str(),
            info.details.c_str()};
}

}  // namespace trn::capi
