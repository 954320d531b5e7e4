// Work shapes of the device Sobel kernels; see sobel_work_shape.hpp.
#include "sobel_work_shape.hpp"
#include "pow2.hpp"

#include <algorithm>

namespace trn {
namespace {

std::size_t ceil_div(std::size_t a, std::size_t b) { return (a + b - 1) / b; }

}  // namespace

SobelWorkShape choose_sobel_work_shape(const WorkGroupLimits& limits, std::size_t width, std::size_t height) {
    constexpr std::size_t kMaxGroup = 256, kGroupsPerUnit = 4, kGroupsWhenUnknown = 64;
    SobelWorkShape s;
    const std::size_t group = floor_pow2(std::clamp<std::size_t>(limits.max_group_size, 1, kMaxGroup));
    s.group_x = std::min(group, floor_pow2(std::max<std::size_t>(limits.lanes, 1)));
    s.group_y = std::min(group / s.group_x, floor_pow2(std::max<std::size_t>(limits.max_group_y, 1)));

    const std::size_t strips = ceil_div(std::max<std::size_t>(width, 1), kSobelStripPixels);
    const std::size_t rows = std::max<std::size_t>(height, 1);
    const std::size_t groups_wanted = limits.compute_units ? kGroupsPerUnit * limits.compute_units : kGroupsWhenUnknown;
    const std::size_t items_wanted = groups_wanted * group;
    s.rows_per_item = std::clamp<std::size_t>(strips * rows / items_wanted, 1, kSobelMaxRowsPerItem);

    s.groups_x = ceil_div(strips, s.group_x);
    s.groups_y = ceil_div(ceil_div(rows, s.rows_per_item), s.group_y);
    return s;
}

}  // namespace trn
