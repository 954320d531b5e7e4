// The quick and the full sweep. The quick one keeps every target of issue 6 measurable
// (1080p Sobel hot and cold, 640x480 NCC dense and sparse, every peer, STREAM) in under two minutes.
#include "sweep.hpp"

#include <algorithm>
#include <cstdlib>
#include <string>

#include "trn/error.hpp"

namespace trn::bench {

std::size_t cold_working_set_bytes() {
    constexpr std::size_t MiB = std::size_t(1) << 20;
    if (const char* env = std::getenv("TRN_BENCH_COLD_MB"); env && *env) {
        char* end = nullptr;
        const long mb = std::strtol(env, &end, 10);
        if (*end != '\0' || mb < 16 || mb > 65536)
            throw Error(std::string("TRN_BENCH_COLD_MB='") + env + "': expected a whole number of MiB in [16, 65536]");
        return std::size_t(mb) * MiB;
    }
    // Not derived from the reported LLC: VMs often report the whole host socket's L3 (508 MiB on
    // the dev VM, whose read bandwidth is flat beyond 24 MiB). 256 MiB is 8x a 32 MiB CCD L3.
    return 256 * MiB;
}

Sweep make_sweep(bool full) {
    Sweep s;
    s.full = full;
    s.cold_bytes = cold_working_set_bytes();
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
    }
    return s;
}

}  // namespace trn::bench
