#pragma once
// Internal: the capability a device backend adds to Backend to measure its copy bandwidth
// (trn/copy_bandwidth.hpp), and the statistics every such backend reports from the device-clock
// seconds of its timed copies.
#include <string>
#include <vector>

#include "trn/copy_bandwidth.hpp"

namespace trn {

class CopyBandwidthProbe {
public:
    virtual ~CopyBandwidthProbe() = default;
    // Arguments already checked by measure_copy_bandwidth.
    virtual CopyBandwidth probe_copy_bandwidth(std::size_t bytes, int repetitions) = 0;
};

CopyBandwidth copy_bandwidth_from(std::size_t bytes, std::vector<double> seconds, std::string method);

}  // namespace trn
