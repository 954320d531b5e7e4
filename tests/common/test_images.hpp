#pragma once
// Test images: owned 8-bit buffers with optional padding (for stride/ROI cases) and textures
// that give NCC something to find.
#include <cstdint>
#include <random>
#include <vector>

#include <opencv2/core.hpp>
#include <opencv2/imgproc.hpp>

#include "trn/image.hpp"

namespace trn::test {

// An image inside a larger buffer: `pad` columns/rows around it, so view().stride > width.
struct PaddedGray {
    int width = 0, height = 0, pad = 0;
    std::vector<std::uint8_t> buffer;
    std::ptrdiff_t stride() const { return width + 2 * pad; }
    std::uint8_t* origin() { return buffer.data() + pad * stride() + pad; }
    GrayView view() const { return {buffer.data() + pad * stride() + pad, width, height, stride()}; }
    cv::Mat mat() const { return cv::Mat(height, width, CV_8UC1, const_cast<std::uint8_t*>(view().data), stride()); }
};

// Smooth random texture: blurred uniform noise stretched to 10..245 plus `edges` straight lines
// (grey and width 1..max_line_width random), like roads and roofs: what aerial imagery looks like
// to NCC. The one texture generator of the tests and the benchmarks (bench/inputs.cpp); cv::RNG
// and the draws' fixed order keep the pixels the same for a seed with every compiler.
inline cv::Mat textured_mat(int w, int h, std::uint64_t seed, int edges, int max_line_width) {
    cv::Mat noise(h, w, CV_32FC1);
    cv::RNG rng(seed);
    rng.fill(noise, cv::RNG::UNIFORM, 0.0, 255.0);
    cv::GaussianBlur(noise, noise, cv::Size(0, 0), 2.0);
    cv::normalize(noise, noise, 10, 245, cv::NORM_MINMAX);
    cv::Mat u8;
    noise.convertTo(u8, CV_8UC1);
    // One draw per statement: the order of a call's arguments is unspecified, and GCC on x86-64
    // (right to left) draws them in another order than GCC on aarch64 or Clang. This is the order
    // the images always had with GCC on x86-64.
    for (int k = 0; k < edges; ++k) {
        const int ay = rng.uniform(0, h), ax = rng.uniform(0, w), by = rng.uniform(0, h), bx = rng.uniform(0, w);
        const int width = 1 + rng.uniform(0, max_line_width), grey = rng.uniform(0, 256);
        cv::line(u8, cv::Point(ax, ay), cv::Point(bx, by), cv::Scalar(grey), width);
    }
    return u8;
}

// textured_mat with six edges up to 3 px wide, in a PaddedGray.
inline PaddedGray textured_image(int w, int h, std::uint32_t seed, int pad = 0) {
    PaddedGray img{w, h, pad, std::vector<std::uint8_t>(std::size_t(w + 2 * pad) * (h + 2 * pad), 0xA5)};
    textured_mat(w, h, seed, 6, 3).copyTo(img.mat());
    return img;
}

// Uniform random bytes: worst case for Sobel ranges.
inline PaddedGray noise_image(int w, int h, std::uint32_t seed, int pad = 0) {
    PaddedGray img{w, h, pad, std::vector<std::uint8_t>(std::size_t(w + 2 * pad) * (h + 2 * pad), 0x5A)};
    std::mt19937 rng(seed);
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) img.origin()[y * img.stride() + x] = static_cast<std::uint8_t>(rng() & 0xFF);
    return img;
}

}  // namespace trn::test
