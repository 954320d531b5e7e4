// trn::load_validity (maps' no-data from alpha and --nodata levels) against its definition computed
// from cv::imread(IMREAD_UNCHANGED); the device kit's libpng reader runs the same cases.
#include <gtest/gtest.h>

#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <vector>

#include "../common/validity_reference.hpp"
#include "trn/error.hpp"
#include "trn/io/image_io.hpp"

TEST(LoadValidity, EveryColourTypeAndTheRealMaps) {
    const std::string dir = testing::TempDir() + "/trn-validity-" + std::to_string(::getpid());
    std::filesystem::create_directories(dir);
    trn::test::check_validity_cases(dir);
    std::filesystem::remove_all(dir);
}

namespace {

std::uint32_t png_crc(const std::string& bytes) {
    std::uint32_t c = 0xFFFFFFFFu;
    for (const unsigned char b : bytes) {
        c ^= b;
        for (int k = 0; k < 8; ++k) c = (c >> 1) ^ (0xEDB88320u & (0u - (c & 1u)));
    }
    return c ^ 0xFFFFFFFFu;
}

std::string be32(std::uint32_t v) { return {char(v >> 24), char(v >> 16), char(v >> 8), char(v)}; }

// `png` (OpenCV's bytes) with a chunk of `type` and `data` inserted after IHDR.
std::string with_chunk(const std::string& png, const std::string& type, const std::string& data) {
    return png.substr(0, 33) + be32(std::uint32_t(data.size())) + type + data + be32(png_crc(type + data)) + png.substr(33);
}

std::string temp_path(const std::string& name) { return testing::TempDir() + "/trn-validity-" + std::to_string(::getpid()) + "-" + name; }

#define EXPECT_HAS(text, part) EXPECT_NE(std::string(text).find(part), std::string::npos) << (text)

}  // namespace

// Issue 45, class 8: a grey PNG's transparency (a tRNS chunk naming one grey level) is no-data, as
// an alpha channel is; OpenCV does not turn it into alpha, and load_validity ignored it.
TEST(LoadValidity, GreyPngTransparencyIsNoData) {
    cv::Mat m(20, 30, CV_8UC1, cv::Scalar(10));
    m(cv::Rect(5, 5, 4, 3)).setTo(77);
    std::vector<uchar> bytes;
    ASSERT_TRUE(cv::imencode(".png", m, bytes));
    const std::string path = temp_path("trns.png");
    {
        std::ofstream(path, std::ios::binary) << with_chunk(std::string(bytes.begin(), bytes.end()), "tRNS", std::string("\0\x4d", 2));
    }
    const trn::GrayImage valid = trn::load_validity(path);
    ASSERT_EQ(valid.width, 30);
    long zero = 0;
    for (const auto v : valid.pixels) zero += v == 0;
    EXPECT_EQ(zero, 12);
    EXPECT_EQ(valid.pixels[std::size_t(6) * 30 + 6], 0);
    EXPECT_EQ(valid.pixels[0], 255);
    std::filesystem::remove(path);
}

// Issue 45, class 5: the no-data mask was read at the file's full depth (16-bit RGBA: 8 B/px, then
// their high bytes and the mask, 13 B/px): a 16384x16384 map took 3.5 GB, then was refused by the
// budget. A PNG's mask is now streamed (the mask and one row): that map's mask is ~268 MB and is
// read; an interlaced PNG still needs every row (8-bit RGBA and the mask, 5 B/px), checked against
// the per-image budget from the header before any decoder runs.
namespace {
// A PNG signature and IHDR of `side`^2 16-bit RGBA, then nothing (libpng stops at the missing IDAT).
std::string rgba16_header(int side, bool interlaced) {
    std::string ihdr = be32(std::uint32_t(side)) + be32(std::uint32_t(side)) + std::string{16, 6, 0, 0, char(interlaced ? 1 : 0)};
    return std::string("\x89PNG\r\n\x1a\n", 8) + be32(13) + "IHDR" + ihdr + be32(png_crc("IHDR" + ihdr));
}
}  // namespace

TEST(LoadValidity, PngMaskIsStreamedWithinTheImageBudget) {
    const std::string path = temp_path("rgba16.png");
    std::ofstream(path, std::ios::binary) << rgba16_header(16384, false);
    try {
        trn::load_validity(path);
        ADD_FAILURE() << "a PNG without image data was read";
    } catch (const trn::Error& e) {  // past the budget, to libpng, which finds no image data
        EXPECT_HAS(e.what(), "rgba16.png: cannot decode PNG");
    }
    std::ofstream(path, std::ios::binary | std::ios::trunc) << rgba16_header(32768, true);
    try {
        trn::load_validity(path);
        ADD_FAILURE() << "a 32768x32768 interlaced 16-bit RGBA mask read was not refused";
    } catch (const trn::Error& e) {
        EXPECT_HAS(e.what(), "rgba16.png: image 32768x32768 (PNG, 4 channels of 16 bits) needs ~5.4 GB to read its no-data mask (limit 2.1 GB per image)");
    }
    std::filesystem::remove(path);
}
