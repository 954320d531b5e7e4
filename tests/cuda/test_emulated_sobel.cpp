// kernels/cuda/sobel3x3.cu run on the CPU (kernel_emulator.hpp) in the backend's layout
// (plan_sobel: padded source rows, the border pass, then the strips), against cpu-ref bit for bit on
// sizes around the 16-pixel strip and the 1-pixel edge cases.
#include <gtest/gtest.h>

#include <cstring>
#include <memory>
#include <vector>

#include "cuda_plan.hpp"
#include "trn/registry.hpp"

#include "kernel_emulator.hpp"
#include "sobel3x3.cu"

namespace trn::cuda {
namespace {

TEST(EmulatedSobel, MatchesCpuRefBits) {
    const std::unique_ptr<Backend> ref = default_registry().create("cpu-ref");
    WorkGroupLimits lim;
    lim.max_group_size = 256;
    lim.lanes = 32;
    lim.compute_units = 2;  // few units: several rows per thread
    lim.max_group_y = 1024;
    for (const auto& [w, h] : {std::pair<int, int>{1, 1}, {1, 7}, {7, 1}, {2, 2}, {15, 9}, {16, 16}, {17, 33}, {50, 40}, {129, 65}}) {
        SCOPED_TRACE(std::to_string(w) + "x" + std::to_string(h));
        std::vector<std::uint8_t> src(std::size_t(w) * h);
        for (std::size_t i = 0; i < src.size(); ++i) src[i] = std::uint8_t((i * 97 + i / 7 * 31) % 256);
        const GrayView view{src.data(), w, h, w};
        std::vector<std::int16_t> want_x(src.size()), want_y(src.size());
        ref->sobel(view, {want_x.data(), w, h, w}, {want_y.data(), w, h, w});

        SobelLaunch l = plan_sobel(std::size_t(w), std::size_t(h), lim, {});
        std::vector<std::uint8_t> padded(l.src_bytes, 0xAB);  // device memory is not cleared either
        for (int y = 0; y < h; ++y) std::memcpy(&padded[std::size_t(y) * l.args.pitch + TRN_SOBEL_PAD], src.data() + std::size_t(y) * w, w);
        std::vector<std::int16_t> gx(l.out_bytes / 2), gy(l.out_bytes / 2);
        l.args.src = reinterpret_cast<std::uintptr_t>(padded.data());
        l.args.gx = reinterpret_cast<std::uintptr_t>(gx.data());
        l.args.gy = reinterpret_cast<std::uintptr_t>(gy.data());
        trn_emu::launch(&sobel3x3_columns, dim3{unsigned(l.columns_grid), 1, 1}, dim3{unsigned(l.columns_block), 1, 1}, l.args);
        trn_emu::launch(&sobel3x3, dim3{unsigned(l.shape.groups_x), unsigned(l.shape.groups_y), 1},
                        dim3{unsigned(l.shape.group_x), unsigned(l.shape.group_y), 1}, l.args);
        int wrong = 0;
        for (int y = 0; y < h; ++y)
            for (int x = 0; x < w; ++x) {
                const std::size_t at = std::size_t(y) * l.args.out_pitch + x, ref_at = std::size_t(y) * w + x;
                wrong += gx[at] != want_x[ref_at] || gy[at] != want_y[ref_at];
            }
        EXPECT_EQ(wrong, 0) << "pixels differ; rows per thread " << l.shape.rows_per_item;
    }
}

}  // namespace
}  // namespace trn::cuda
