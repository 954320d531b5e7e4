// Vulkan 3x3 Sobel: the image goes through in bands of rows, each with one reflect-101 halo row
// above and below and a reflected neighbour byte left and right of every row, all written on the
// host while copying the band in (sobel3x3.comp has no border branches). Images of any size fit
// the device's buffer limits and the per-call buffers stay bounded.
#include <algorithm>
#include <cstring>

#include "../common/sobel_work_shape.hpp"
#include "vulkan_backend_impl.hpp"

namespace trn::vk {
namespace {

struct SobelPush {  // matches the push_constant block of sobel3x3.comp
    std::uint32_t width, rows, src_pitch, out_pitch, rows_per_item;
};

// reflect-101: -1 -> 1, n -> n-2; an axis of length 1 maps every index to 0.
int reflect101(int i, int n) { return n == 1 ? 0 : i < 0 ? -i : i >= n ? 2 * n - 2 - i : i; }

constexpr std::size_t kBandPixels = std::size_t(1) << 24;  // bounds the band buffers (~80 MB)

}  // namespace

WorkGroupLimits sobel_work_group_limits(const Context& ctx) {
    const auto& lim = ctx.limits();
    WorkGroupLimits limits;
    limits.max_group_size = ctx.max_linear_group();
    limits.max_group_y = lim.maxComputeWorkGroupSize[1];
    limits.lanes = ctx.subgroup_lanes();
    limits.compute_units = 0;  // Vulkan core has no such query
    return limits;
}

void VulkanBackend::do_sobel(GrayView src, Int16View gx, Int16View gy, PhaseTimes* times) {
    Context& ctx = *context_;
    const auto& lim = ctx.limits();
    const std::size_t w = static_cast<std::size_t>(src.width), h = static_cast<std::size_t>(src.height);
    const std::size_t strips = (w + kSobelStripPixels - 1) / kSobelStripPixels;
    const std::size_t src_pitch = 4 * strips + 8;  // words: left block, the strips, right block
    const std::size_t out_words = 8 * strips;      // two int16 per word
    const std::size_t range = lim.maxStorageBufferRange / 4;  // in words
    const std::size_t group_y = sobel_shape_.group_y;
    std::size_t band = std::min({h, std::max<std::size_t>(1, kBandPixels / w), range / src_pitch - 2, range / out_words,
                                 std::size_t(lim.maxComputeWorkGroupCount[1]) * group_y});
    if (band == 0 || range / src_pitch < 3) throw Error("sobel: image rows of " + std::to_string(w) + " pixels are too wide for " + info_.name);
    const std::size_t groups_x = (strips + sobel_shape_.group_x - 1) / sobel_shape_.group_x;
    if (groups_x > lim.maxComputeWorkGroupCount[0])
        throw Error("sobel: image width " + std::to_string(w) + " exceeds what one dispatch on " + info_.name + " covers");

    sobel_src_->ensure((band + 2) * src_pitch * 4);
    sobel_gx_->ensure(band * out_words * 4);
    sobel_gy_->ensure(band * out_words * 4);
    sobel_kernel_->bind({sobel_src_->device(), sobel_gx_->device(), sobel_gy_->device()});
    const VkPipeline pipeline =
        sobel_kernel_->pipeline({static_cast<std::uint32_t>(sobel_shape_.group_x), static_cast<std::uint32_t>(group_y)});

    double upload_ms = 0, execute_ms = 0, download_ms = 0;
    const int wi = src.width;
    const std::size_t left = static_cast<std::size_t>(reflect101(-1, wi)), right = static_cast<std::size_t>(reflect101(wi, wi));
    for (std::size_t y0 = 0; y0 < h; y0 += band) {
        const std::size_t rows = std::min(band, h - y0);
        const SobelWorkShape shape = choose_sobel_work_shape(sobel_limits_, w, rows);
        auto t0 = Clock::now();
        auto* dst = static_cast<std::uint8_t*>(sobel_src_->host());
        for (std::size_t r = 0; r < rows + 2; ++r) {  // source rows y0-1 .. y0+rows, reflected
            const std::uint8_t* row = src.row(reflect101(static_cast<int>(y0 + r) - 1, static_cast<int>(h)));
            std::uint8_t* out = dst + r * src_pitch * 4;
            out[15] = row[left];
            std::memcpy(out + 16, row, w);
            out[16 + w] = row[right];
        }
        upload_ms += ms_since(t0);

        const SobelPush push{static_cast<std::uint32_t>(w), static_cast<std::uint32_t>(rows), static_cast<std::uint32_t>(src_pitch / 4),
                             static_cast<std::uint32_t>(out_words / 4), static_cast<std::uint32_t>(shape.rows_per_item)};
        VkCommandBuffer cmd = recorder_->begin();
        recorder_->mark(0);
        sobel_src_->record_upload(cmd, (rows + 2) * src_pitch * 4);
        barrier_after_upload();
        recorder_->mark(1);
        sobel_kernel_->record_dispatch(cmd, pipeline, &push, static_cast<std::uint32_t>(shape.groups_x),
                                       static_cast<std::uint32_t>(shape.groups_y));
        barrier_after_execute();
        recorder_->mark(2);
        sobel_gx_->record_download(cmd, rows * out_words * 4);
        sobel_gy_->record_download(cmd, rows * out_words * 4);
        barrier_after_download();
        recorder_->mark(3);
        t0 = Clock::now();
        recorder_->submit_and_wait("vkQueueSubmit (sobel)");
        const double wall_ms = ms_since(t0);
        upload_ms += recorder_->elapsed_ms(0, 1);
        execute_ms += recorder_->has_timestamps() ? recorder_->elapsed_ms(1, 2) : wall_ms;
        download_ms += recorder_->elapsed_ms(2, 3);

        // The words are little-endian int16 pairs: each output row is a plain int16 row of pitch 2*out_words.
        t0 = Clock::now();
        const auto* rx = static_cast<const std::int16_t*>(sobel_gx_->host());
        const auto* ry = static_cast<const std::int16_t*>(sobel_gy_->host());
        for (std::size_t r = 0; r < rows; ++r) {
            std::memcpy(gx.row(static_cast<int>(y0 + r)), rx + r * 2 * out_words, w * sizeof(std::int16_t));
            std::memcpy(gy.row(static_cast<int>(y0 + r)), ry + r * 2 * out_words, w * sizeof(std::int16_t));
        }
        download_ms += ms_since(t0);
    }
    if (times) *times = {upload_ms, execute_ms, download_ms};
    ctx.throw_on_validation_messages("sobel");
}

}  // namespace trn::vk
