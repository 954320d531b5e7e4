// The device kit's libtrnkit_io (PNG through libpng, no OpenCV imgcodecs) reads every PNG as the
// normal build does (cv::imread IMREAD_GRAYSCALE, the reference here): the real maps and frames of
// ../shared/data and PNGs of every colour type and depth written here; it refuses other formats
// by name. This binary links the kit's io library, never the normal one.
#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>
#include <random>

#include "../common/validity_reference.hpp"
#include "trn/error.hpp"
#include "trn/io/image_io.hpp"
#include "../common/shared_data.hpp"

namespace fs = std::filesystem;

namespace {

fs::path temp_dir() {
    static const fs::path dir = [] {
        fs::path d = fs::temp_directory_path() / ("trn-png-codec-" + std::to_string(::getpid()));
        fs::create_directories(d);
        return d;
    }();
    return dir;
}

void expect_same_as_opencv(const std::string& path) {
    SCOPED_TRACE(path);
    const cv::Mat ref = cv::imread(path, cv::IMREAD_GRAYSCALE);
    ASSERT_FALSE(ref.empty());
    const trn::GrayImage img = trn::load_gray(path);
    ASSERT_EQ(img.width, ref.cols);
    ASSERT_EQ(img.height, ref.rows);
    long differing = 0;
    for (int y = 0; y < ref.rows; ++y)
        for (int x = 0; x < ref.cols; ++x) differing += img.pixels[std::size_t(y) * img.width + x] != ref.at<std::uint8_t>(y, x);
    EXPECT_EQ(differing, 0) << "pixels differ from cv::imread";
}

cv::Mat noise(int rows, int cols, int type, unsigned seed) {
    cv::Mat m(rows, cols, type);
    cv::RNG rng(seed);
    rng.fill(m, cv::RNG::UNIFORM, 0, CV_MAT_DEPTH(type) == CV_16U ? 65536 : 256);
    return m;
}

}  // namespace

TEST(DeviceKitPng, RealMapsAndFramesReadAsOpenCvReadsThem) {
    const fs::path base = trn::test::shared_data_dir();
    std::vector<fs::path> files = {base / "orthophoto.png", base / "realflight/frame_00000.png",
                                   base / "realflight2/orthomosaic.png", base / "realflight2/frames/frame_00000.png"};
    int found = 0;
    for (const fs::path& f : files)
        if (fs::exists(f)) ++found, expect_same_as_opencv(f.string());
    if (found == 0) GTEST_SKIP() << "shared data not found (TRN_SHARED_DATA='" << base.string() << "')";
}

TEST(DeviceKitPng, EveryColourTypeAndDepthReadsAsOpenCvReadsIt) {
    const std::vector<std::pair<const char*, int>> kinds = {
        {"grey8", CV_8UC1}, {"grey16", CV_16UC1}, {"rgb8", CV_8UC3}, {"rgb16", CV_16UC3}, {"rgba8", CV_8UC4}, {"rgba16", CV_16UC4}};
    unsigned seed = 1;
    for (const auto& [name, type] : kinds) {
        const std::string path = (temp_dir() / (std::string(name) + ".png")).string();
        ASSERT_TRUE(cv::imwrite(path, noise(37, 53, type, seed++)));
        expect_same_as_opencv(path);
    }
    // Interlaced and palette PNGs cannot be written by OpenCV; a 1-bit grey image can.
    const std::string bilevel = (temp_dir() / "bilevel.png").string();
    cv::Mat b = noise(16, 16, CV_8UC1, 9) > 127;
    ASSERT_TRUE(cv::imwrite(bilevel, b, {cv::IMWRITE_PNG_BILEVEL, 1}));
    expect_same_as_opencv(bilevel);
}

// No-data (alpha 0, --nodata levels) as the normal build reads it (tests/unit/test_load_validity.cpp).
TEST(DeviceKitPng, NoDataReadsAsOpenCvReadsIt) { trn::test::check_validity_cases(temp_dir().string()); }

TEST(DeviceKitPng, WrittenPngsReadBackExactly) {
    const cv::Mat m = noise(21, 34, CV_8UC1, 5);
    const std::string path = (temp_dir() / "written.png").string();
    trn::save_gray(path, {m.data, m.cols, m.rows, static_cast<std::ptrdiff_t>(m.step)});
    expect_same_as_opencv(path);
    const trn::GrayImage back = trn::load_gray(path);
    EXPECT_TRUE(std::equal(back.pixels.begin(), back.pixels.end(), m.data));
}

TEST(DeviceKitPng, OtherFormatsAreRefusedByName) {
    const cv::Mat m = noise(8, 8, CV_8UC1, 3);
    const std::string jpg = (temp_dir() / "frame.jpg").string();
    ASSERT_TRUE(cv::imwrite(jpg, m));
    try {
        trn::load_gray(jpg);
        FAIL() << "a JPEG was read";
    } catch (const trn::Error& e) {
        EXPECT_NE(std::string(e.what()).find(jpg + ": not a PNG file"), std::string::npos) << e.what();
    }
    try {
        trn::save_gray((temp_dir() / "out.jpg").string(), {m.data, m.cols, m.rows, static_cast<std::ptrdiff_t>(m.step)});
        FAIL() << "a JPEG was written";
    } catch (const trn::Error& e) {
        EXPECT_NE(std::string(e.what()).find("writes PNG only"), std::string::npos) << e.what();
    }
    // A cut PNG is an error naming the file, not a crash or a partial image.
    const std::string whole = (temp_dir() / "whole.png").string(), cut = (temp_dir() / "cut.png").string();
    ASSERT_TRUE(cv::imwrite(whole, noise(64, 64, CV_8UC1, 4)));
    std::ifstream in(whole, std::ios::binary);
    std::string bytes((std::istreambuf_iterator<char>(in)), {});
    std::ofstream(cut, std::ios::binary).write(bytes.data(), std::streamsize(bytes.size() / 2));
    try {
        trn::load_gray(cut);
        FAIL() << "a cut PNG was read";
    } catch (const trn::Error& e) {
        EXPECT_NE(std::string(e.what()).find(cut + ": cannot decode PNG"), std::string::npos) << e.what();
    }
}
