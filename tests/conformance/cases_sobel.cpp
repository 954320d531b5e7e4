// Sobel cases: every size class (1x1, 1xN, Nx1, odd, HD), strided sources and outputs with guard
// bands, extreme content; bit-exact against cv::Sobel and against cpu-ref.
#include <gtest/gtest.h>

#include <opencv2/imgproc.hpp>

#include "../common/test_images.hpp"
#include "cases.hpp"
#include "checks.hpp"

namespace trn::conformance {
namespace {

constexpr std::int16_t kSentinel = 0x5A5A;

// An int16 output image with kGuard sentinel columns left and right and one sentinel row above
// and below, so any write outside the view is caught.
struct GuardedGradient {
    int w, h;
    std::ptrdiff_t stride;
    std::vector<std::int16_t> buf;
    GuardedGradient(int w_, int h_) : w(w_), h(h_), stride(w_ + 2 * kGuard), buf(std::size_t(stride) * (h_ + 2), kSentinel) {}
    Int16View view() { return {buf.data() + stride + kGuard, w, h, stride}; }
    std::int16_t at(int x, int y) const { return buf[std::size_t(y + 1) * stride + kGuard + x]; }
    bool guards_intact() const {
        for (int y = -1; y <= h; ++y)
            for (int x = -kGuard; x < w + kGuard; ++x)
                if ((y < 0 || y >= h || x < 0 || x >= w) && buf[std::size_t(y + 1) * stride + kGuard + x] != kSentinel) return false;
        return true;
    }
};

// Returns the number of pixels differing from cv::Sobel in gx and gy.
void check_sobel(Backend& dut, Backend& ref, const test::PaddedGray& src) {
    const int w = src.width, h = src.height;
    GuardedGradient gx(w, h), gy(w, h), rx(w, h), ry(w, h);
    dut.sobel(src.view(), gx.view(), gy.view());
    ref.sobel(src.view(), rx.view(), ry.view());
    cv::Mat cx, cy;
    cv::Sobel(src.mat(), cx, CV_16S, 1, 0, 3, 1, 0, cv::BORDER_REFLECT_101);
    cv::Sobel(src.mat(), cy, CV_16S, 0, 1, 3, 1, 0, cv::BORDER_REFLECT_101);
    EXPECT_TRUE(gx.guards_intact() && gy.guards_intact()) << dut.info().name << " wrote outside the Sobel output";
    long bad_cv = 0, bad_ref = 0;
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
            bad_cv += gx.at(x, y) != cx.at<std::int16_t>(y, x) || gy.at(x, y) != cy.at<std::int16_t>(y, x);
            bad_ref += gx.at(x, y) != rx.at(x, y) || gy.at(x, y) != ry.at(x, y);
            if (bad_cv == 1 && (gx.at(x, y) != cx.at<std::int16_t>(y, x) || gy.at(x, y) != cy.at<std::int16_t>(y, x)))
                ADD_FAILURE() << w << "x" << h << " first mismatch at (" << x << ", " << y << "): gx " << gx.at(x, y) << " vs cv "
                              << cx.at<std::int16_t>(y, x) << ", gy " << gy.at(x, y) << " vs cv " << cy.at<std::int16_t>(y, x);
        }
    EXPECT_EQ(bad_cv, 0) << w << "x" << h << ": pixels differing from cv::Sobel";
    EXPECT_EQ(bad_ref, 0) << w << "x" << h << ": pixels differing from cpu-ref";
}

void sizes(Backend& dut, Backend& ref) {
    const int dims[][2] = {{1, 1}, {1, 7}, {7, 1}, {2, 2}, {3, 3}, {1, 300}, {300, 1}, {17, 5}, {64, 64}, {333, 251}, {640, 480}, {1920, 1080}};
    std::uint32_t seed = 1;
    for (const auto& d : dims) {
        SCOPED_TRACE(std::to_string(d[0]) + "x" + std::to_string(d[1]));
        check_sobel(dut, ref, test::noise_image(d[0], d[1], seed++, 3));  // padded: stride > width
    }
}

// The device kernels work on 16-pixel strips over blocks of rows (sobel_work_shape.hpp): widths
// on both sides of strip multiples, every small height, and images big enough that one work item
// covers several rows with a partial last block.
void strip_edges(Backend& dut, Backend& ref) {
    const int widths[] = {2, 3, 4, 5, 8, 12, 15, 16, 17, 18, 20, 31, 32, 33, 47, 48, 49, 63, 64, 65};
    const int heights[] = {1, 2, 3, 4, 5, 17};
    std::uint32_t seed = 100;
    for (int w : widths)
        for (int h : heights) {
            SCOPED_TRACE(std::to_string(w) + "x" + std::to_string(h));
            check_sobel(dut, ref, test::noise_image(w, h, seed++, 1 + (w % 3)));
        }
    const int tall[][2] = {{1, 33}, {2, 31}, {1001, 77}, {1283, 721}, {2050, 9}, {9, 2050}};
    for (const auto& d : tall) {
        SCOPED_TRACE(std::to_string(d[0]) + "x" + std::to_string(d[1]));
        check_sobel(dut, ref, test::noise_image(d[0], d[1], seed++, 5));
    }
}

void extremes(Backend& dut, Backend& ref) {
    test::PaddedGray board = test::noise_image(65, 33, 5, 2);
    for (int y = 0; y < 33; ++y)
        for (int x = 0; x < 65; ++x) board.origin()[y * board.stride() + x] = ((x + y) & 1) ? 255 : 0;
    check_sobel(dut, ref, board);  // largest gradients
    test::PaddedGray white = test::noise_image(40, 40, 6, 1);
    for (int y = 0; y < 40; ++y)
        for (int x = 0; x < 40; ++x) white.origin()[y * white.stride() + x] = x < 20 ? 255 : 0;
    check_sobel(dut, ref, white);
    check_sobel(dut, ref, test::textured_image(257, 129, 7, 0));  // unpadded
}

}  // namespace

std::vector<Case> sobel_cases() {
    return {{"sobel_sizes_and_strides", sizes}, {"sobel_strip_edges", strip_edges}, {"sobel_extremes", extremes}};
}

}  // namespace trn::conformance
