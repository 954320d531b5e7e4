// Vulkan 3x3 Sobel: the image goes through in bands of rows, each with one reflect-101 halo row
// above and below chosen on the host (sobel3x3.comp reflects columns only), so images of any size
// fit the device's buffer limits and the per-call buffers stay bounded.
#include <algorithm>
#include <cstring>

#include "vulkan_backend_impl.hpp"

namespace trn::vk {
namespace {

struct SobelPush {  // matches the push_constant block of sobel3x3.comp
    std::uint32_t width, rows, src_pitch, out_pitch;
};

// reflect-101: -1 -> 1, n -> n-2; an axis of length 1 maps every index to 0.
int reflect101(int i, int n) { return n == 1 ? 0 : i < 0 ? -i : i >= n ? 2 * n - 2 - i : i; }

constexpr std::size_t kBandPixels = std::size_t(1) << 24;  // bounds the band buffers (~80 MB)

}  // namespace

void VulkanBackend::do_sobel(GrayView src, Int16View gx, Int16View gy, PhaseTimes* times) {
    Context& ctx = *context_;
    const auto& lim = ctx.limits();
    const std::size_t w = static_cast<std::size_t>(src.width), h = static_cast<std::size_t>(src.height);
    const std::size_t src_pitch = (w + 3) & ~std::size_t(3);  // bytes per uploaded row
    const std::size_t quads = (w + 3) / 4;                     // one invocation per 4 output pixels
    const std::size_t out_words = 2 * quads;                   // two int16 per word
    const std::size_t range = lim.maxStorageBufferRange;
    std::size_t band = std::min({h, std::max<std::size_t>(1, kBandPixels / w), range / src_pitch - 2,
                                 range / (out_words * 4), std::size_t(lim.maxComputeWorkGroupCount[1]) * sobel_group_y_});
    if (band == 0 || range / src_pitch < 3) throw Error("sobel: image rows of " + std::to_string(w) + " pixels are too wide for " + info_.name);
    const std::uint32_t groups_x = static_cast<std::uint32_t>((quads + sobel_group_x_ - 1) / sobel_group_x_);
    if (groups_x > lim.maxComputeWorkGroupCount[0])
        throw Error("sobel: image width " + std::to_string(w) + " exceeds what one dispatch on " + info_.name + " covers");

    sobel_src_->ensure((band + 2) * src_pitch);
    sobel_gx_->ensure(band * out_words * 4);
    sobel_gy_->ensure(band * out_words * 4);
    sobel_kernel_->bind({sobel_src_->device(), sobel_gx_->device(), sobel_gy_->device()});
    const VkPipeline pipeline = sobel_kernel_->pipeline({sobel_group_x_, sobel_group_y_});

    double upload_ms = 0, execute_ms = 0, download_ms = 0;
    for (std::size_t y0 = 0; y0 < h; y0 += band) {
        const std::size_t rows = std::min(band, h - y0);
        auto t0 = Clock::now();
        auto* dst = static_cast<std::uint8_t*>(sobel_src_->host());
        for (std::size_t r = 0; r < rows + 2; ++r) {  // source rows y0-1 .. y0+rows, reflected
            const int y = reflect101(static_cast<int>(y0 + r) - 1, static_cast<int>(h));
            std::memcpy(dst + r * src_pitch, src.row(y), w);
        }
        upload_ms += ms_since(t0);

        const SobelPush push{static_cast<std::uint32_t>(w), static_cast<std::uint32_t>(rows),
                             static_cast<std::uint32_t>(src_pitch), static_cast<std::uint32_t>(out_words)};
        VkCommandBuffer cmd = recorder_->begin();
        recorder_->mark(0);
        sobel_src_->record_upload(cmd, (rows + 2) * src_pitch);
        barrier_after_upload();
        recorder_->mark(1);
        sobel_kernel_->record_dispatch(cmd, pipeline, &push, groups_x,
                                       static_cast<std::uint32_t>((rows + sobel_group_y_ - 1) / sobel_group_y_));
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
