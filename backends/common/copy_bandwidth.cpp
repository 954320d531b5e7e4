// measure_copy_bandwidth: argument checks, the capability lookup, and the reported statistics.
#include "copy_bandwidth.hpp"

#include <algorithm>

namespace trn {

bool can_measure_copy_bandwidth(const Backend& backend) {
    return dynamic_cast<const CopyBandwidthProbe*>(&backend) != nullptr;
}

CopyBandwidth measure_copy_bandwidth(Backend& backend, std::size_t bytes, int repetitions) {
    if (bytes < 16 || bytes % 16 != 0 || bytes > (std::size_t(4) << 30))
        throw Error("measure_copy_bandwidth: bytes = " + std::to_string(bytes) + ": expected a multiple of 16 from 16 B to 4 GiB");
    if (repetitions < 1 || repetitions > 1000)
        throw Error("measure_copy_bandwidth: repetitions = " + std::to_string(repetitions) + ": expected 1 to 1000");
    auto* probe = dynamic_cast<CopyBandwidthProbe*>(&backend);
    if (!probe)
        throw Error("measure_copy_bandwidth: " + backend.info().name +
                    " works in host memory; its limit is the host's STREAM copy (trn_bench stream/copy)");
    return probe->probe_copy_bandwidth(bytes, repetitions);
}

CopyBandwidth copy_bandwidth_from(std::size_t bytes, std::vector<double> seconds, std::string method) {
    CopyBandwidth r;
    r.bytes = bytes;
    r.repetitions = static_cast<int>(seconds.size());
    r.method = std::move(method);
    std::sort(seconds.begin(), seconds.end());
    if (seconds.empty() || seconds.front() <= 0)
        throw Error("measure_copy_bandwidth: the device clock reported no time for a copy (" + r.method + ")");
    r.best_seconds = seconds.front();
    r.median_seconds = seconds[seconds.size() / 2];
    r.bytes_per_second = 2.0 * double(bytes) / r.best_seconds;
    return r;
}

}  // namespace trn
