#pragma once
// Peak resident memory of this process around one operation (Linux /proc), for tests that check
// memory estimates: reset the high-water mark, run, read how far it rose above the starting RSS.
#include <malloc.h>

#include <cstdint>
#include <fstream>
#include <optional>
#include <string>

namespace trn::test {

// ASan keeps freed blocks in quarantine and pads every allocation, so RSS bounds written for the
// normal allocator do not hold in a sanitized build; tests check what they can and skip the bound.
#if defined(__SANITIZE_ADDRESS__)
inline constexpr bool kUnderAddressSanitizer = true;
#elif defined(__has_feature)
#if __has_feature(address_sanitizer)
inline constexpr bool kUnderAddressSanitizer = true;
#else
inline constexpr bool kUnderAddressSanitizer = false;
#endif
#else
inline constexpr bool kUnderAddressSanitizer = false;
#endif

// What ASan adds to a peak, so that sanitized builds check their own bound instead of skipping:
// its shadow memory is 1/8 of the memory it describes (written whole when a block is freed and
// poisoned, or when its redzones are), so a peak of B bytes of our data may take B * 9/8 resident.
// Freed blocks wait in its quarantine (still resident, up to quarantine_size_mb: 256 MiB by
// default), so tests that free large blocks before the peak either measure a fresh process or
// count that separately.
inline constexpr double kAddressSanitizerRssSlack = 1.125;

// "VmRSS" / "VmHWM" of /proc/self/status in bytes; 0 when absent.
inline std::uint64_t proc_status_bytes(const std::string& key) {
    std::ifstream f("/proc/self/status");
    for (std::string line; std::getline(f, line);)
        if (line.rfind(key + ":", 0) == 0) return std::stoull(line.substr(key.size() + 1)) * 1024;  // "NNN kB"
    return 0;
}

// Bytes the peak RSS rose above the RSS before `work` ran; nullopt when the kernel cannot reset
// the high-water mark (writing 5 to /proc/self/clear_refs, Linux >= 4.0).
template <typename Work>
std::optional<std::uint64_t> peak_rss_growth(Work&& work) {
    malloc_trim(0);  // freed heap memory still counts as resident and would be reused unseen
    {
        std::ofstream clear("/proc/self/clear_refs");
        if (!(clear << "5" << std::flush)) return std::nullopt;
    }
    const std::uint64_t before = proc_status_bytes("VmRSS");
    if (before == 0 || proc_status_bytes("VmHWM") > before + (std::uint64_t(1) << 20)) return std::nullopt;
    work();
    const std::uint64_t peak = proc_status_bytes("VmHWM");
    return peak > before ? peak - before : 0;
}

}  // namespace trn::test
