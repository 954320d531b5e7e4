// The quick and the full sweep. The quick one keeps every target of issues 6 and 14 measurable
// (1080p Sobel hot and cold, 640x480 NCC dense and sparse, every peer, STREAM, and both sweeps
// the filter's 1000 x 160x120 case beside the old cpu path) in a few minutes.
#include "sweep.hpp"

#include <algorithm>
#include <cstdlib>
#include <string>

#include <unistd.h>

#include "trn/error.hpp"
#include "trn/limits.hpp"

namespace trn::bench {

std::size_t cold_working_set_bytes(std::size_t llc, std::size_t physical, std::string& basis) {
    constexpr std::size_t MiB = std::size_t(1) << 20, kFloor = 256 * MiB;
    // The reported LLC may be the whole host socket's (508 MiB on the dev VM, whose read bandwidth
    // is flat beyond 24 MiB); 4x it is beyond any cache the VM can reach either way.
    std::size_t bytes = std::max(kFloor, 4 * llc);
    basis = llc ? "4x the reported " + std::to_string(llc / MiB) + " MiB L3" : "no L3 size reported: 256 MiB";
    if (bytes == kFloor && llc) basis = "256 MiB, more than 4x the reported " + std::to_string(llc / MiB) + " MiB L3";
    if (physical && bytes > physical / 4) {
        bytes = std::max(kFloor, physical / 4 / MiB * MiB);
        basis += ", capped at a quarter of the " + std::to_string(physical / MiB) + " MiB of memory";
    }
    return bytes;
}

std::size_t cold_working_set_bytes(std::string& basis) {
    constexpr std::size_t MiB = std::size_t(1) << 20;
    if (const char* env = std::getenv("TRN_BENCH_COLD_MB"); env && *env) {
        char* end = nullptr;
        const long mb = std::strtol(env, &end, 10);
        if (*end != '\0' || mb < 16 || mb > 65536)
            throw Error(std::string("TRN_BENCH_COLD_MB='") + env + "': expected a whole number of MiB in [16, 65536]");
        basis = "TRN_BENCH_COLD_MB";
        return std::size_t(mb) * MiB;
    }
    const long llc = sysconf(_SC_LEVEL3_CACHE_SIZE);
    return cold_working_set_bytes(llc > 0 ? std::size_t(llc) : 0, std::size_t(limits::physical_memory_bytes()), basis);
}

Sweep make_sweep(bool full) {
    Sweep s;
    s.full = full;
    s.cold_bytes = cold_working_set_bytes(s.cold_basis);
    if (full) {
        s.sobel_sizes = {{640, 480}, {1280, 720}, {1920, 1080}};
        s.sobel_cold_sizes = s.sobel_sizes;
        s.sobel_batch16 = true;
        s.ncc_counts = {100, 1000, 10000};
        s.ncc_templates = {{640, 480}, {400, 400}, {232, 174}};
    } else {
        s.sobel_sizes = {{640, 480}, {1920, 1080}};
        s.sobel_cold_sizes = {{1920, 1080}};
        s.ncc_counts = {100};
        s.ncc_reference_count = 25;  // cpu-ref and particle_match take seconds per 100 particles at 640x480
        s.ncc_templates = {{640, 480}};
        s.latency_steps = 60;  // of realflight3's 167: a pass of the whole flight takes 20-60 s per backend here
    }
    return s;
}

}  // namespace trn::bench
