// Size limits and memory estimates; see trn/limits.hpp.
#include "trn/limits.hpp"

#include <unistd.h>

#include <cmath>
#include <cstdio>

#include "trn/error.hpp"

namespace trn::limits {
namespace {

std::string size_text(std::int64_t w, std::int64_t h) { return std::to_string(w) + "x" + std::to_string(h); }

// "1073741824 pixels, e.g. 32768x32768" (the example is the square with that many pixels, when one exists).
std::string pixel_limit_text(std::int64_t max_pixels) {
    const auto side = static_cast<std::int64_t>(std::llround(std::sqrt(static_cast<double>(max_pixels))));
    std::string text = std::to_string(max_pixels) + " pixels";
    if (side * side == max_pixels) text += ", e.g. " + size_text(side, side);
    return text;
}

}  // namespace

std::uint64_t physical_memory_bytes() {
    static const std::uint64_t bytes = [] {  // does not change while we run
        const long pages = sysconf(_SC_PHYS_PAGES), page = sysconf(_SC_PAGESIZE);
        return pages <= 0 || page <= 0 ? std::uint64_t(0) : static_cast<std::uint64_t>(pages) * static_cast<std::uint64_t>(page);
    }();
    return bytes;
}

std::string format_bytes(double bytes) {
    static const char* const units[] = {"B", "kB", "MB", "GB", "TB", "PB"};
    int u = 0;
    while (bytes >= 1000 && u < 5) bytes /= 1000, ++u;
    char buf[32];
    std::snprintf(buf, sizeof buf, bytes < 10 && u > 0 ? "%.1f %s" : "%.0f %s", bytes, units[u]);
    return buf;
}

static_assert(kMaxMemoryShare == 0.5, "the message below says 'half'");

// The checks allocate nothing unless they throw: they run on every score / sobel call, and
// steady-state calls must not allocate (tests/vulkan/test_vulkan_allocations.cpp).

void check_memory(std::string_view what, double bytes, std::uint64_t physical) {
    if (physical == 0) return;
    const double limit = kMaxMemoryShare * static_cast<double>(physical);
    if (bytes > limit)
        throw Error(std::string(what) + " needs ~" + format_bytes(bytes) + " (limit " + format_bytes(limit) +
                    ", half of this machine's " + format_bytes(static_cast<double>(physical)) + " of memory)");
}

void check_image(std::string_view what, std::int64_t width, std::int64_t height, std::int64_t max_pixels,
                 double bytes_per_pixel) {
    auto sized = [&] { return std::string(what) + " " + size_text(width, height); };
    if (width <= 0 || height <= 0) throw Error(sized() + " is empty");
    if (width > kMaxImageSide || height > kMaxImageSide)
        throw Error(sized() + " is too large: its sides may be at most " + std::to_string(kMaxImageSide) + " pixels");
    const double bytes = bytes_per_pixel * static_cast<double>(width) * static_cast<double>(height);
    if (width * height > max_pixels)
        throw Error(sized() + " needs ~" + format_bytes(bytes) + " (limit " + pixel_limit_text(max_pixels) + ")");
    if (physical_memory_bytes() != 0 && bytes > kMaxMemoryShare * static_cast<double>(physical_memory_bytes()))
        check_memory(sized(), bytes);
}

void check_count(std::string_view what, std::int64_t count, std::int64_t max, double bytes_each) {
    auto counted = [&] { return std::string(what) + " " + std::to_string(count); };
    const double bytes = bytes_each * static_cast<double>(count);
    if (count > max) throw Error(counted() + " needs ~" + format_bytes(bytes) + " (limit " + std::to_string(max) + ")");
    if (physical_memory_bytes() != 0 && bytes > kMaxMemoryShare * static_cast<double>(physical_memory_bytes()))
        check_memory(counted(), bytes);
}

}  // namespace trn::limits
