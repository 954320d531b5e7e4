#pragma once
// What trn::load_validity must return for a file, computed from cv::imread(IMREAD_UNCHANGED): 0
// where alpha is 0 or every colour channel equals nodata, 255 elsewhere; empty when the file has no
// alpha and no nodata is given. Shared by the normal build's test and the device kit's (libpng).
#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include <opencv2/imgcodecs.hpp>
#include <png.h>

#include "trn/error.hpp"
#include "trn/io/image_io.hpp"
#include "shared_data.hpp"

namespace trn::test {

inline cv::Mat validity_reference(const std::string& path, std::optional<int> nodata) {
    cv::Mat m = cv::imread(path, cv::IMREAD_UNCHANGED);
    if (m.depth() == CV_16U) {  // the high byte, as load_gray reads 16-bit files
        cv::Mat high(m.rows, m.cols, CV_MAKETYPE(CV_8U, m.channels()));
        for (int y = 0; y < m.rows; ++y)
            for (int i = 0; i < m.cols * m.channels(); ++i) high.ptr<std::uint8_t>(y)[i] = std::uint8_t(m.ptr<std::uint16_t>(y)[i] >> 8);
        m = high;
    }
    const int ch = m.channels();
    const bool alpha = ch == 2 || ch == 4;
    if (!alpha && !nodata) return {};
    cv::Mat out(m.rows, m.cols, CV_8UC1, cv::Scalar(255));
    for (int y = 0; y < m.rows; ++y)
        for (int x = 0; x < m.cols; ++x) {
            const std::uint8_t* p = m.ptr<std::uint8_t>(y) + std::size_t(x) * ch;
            bool bad = alpha && p[ch - 1] == 0;
            if (nodata && !bad) {
                bad = true;
                for (int c = 0; c < (alpha ? ch - 1 : ch); ++c) bad = bad && p[c] == *nodata;
            }
            if (bad) out.at<std::uint8_t>(y, x) = 0;
        }
    return out;
}

inline void expect_validity_as_reference(const std::string& path, std::optional<int> nodata) {
    SCOPED_TRACE(path + (nodata ? " nodata " + std::to_string(*nodata) : ""));
    const cv::Mat want = validity_reference(path, nodata);
    const GrayImage got = load_validity(path, nodata);
    if (want.empty()) {
        EXPECT_EQ(got.width, 0) << "no alpha and no nodata: expected no mask";
        return;
    }
    ASSERT_EQ(got.width, want.cols);
    ASSERT_EQ(got.height, want.rows);
    long differing = 0;
    for (int y = 0; y < want.rows; ++y)
        for (int x = 0; x < want.cols; ++x) differing += got.pixels[std::size_t(y) * got.width + x] != want.at<std::uint8_t>(y, x);
    EXPECT_EQ(differing, 0);
}

// `m` (8- or 16-bit, 1 or 4 channels, OpenCV's BGRA order) as an Adam7-interlaced PNG, which
// cv::imwrite cannot write: the mask reader's interlaced path.
inline void write_interlaced_png(const std::string& path, const cv::Mat& m) {
    std::FILE* f = std::fopen(path.c_str(), "wb");
    ASSERT_NE(f, nullptr) << path;
    png_structp png = png_create_write_struct(PNG_LIBPNG_VER_STRING, nullptr, nullptr, nullptr);
    png_infop info = png_create_info_struct(png);
    std::vector<png_bytep> rows(m.rows);
    for (int y = 0; y < m.rows; ++y) rows[y] = const_cast<png_bytep>(m.ptr<png_byte>(y));
    png_init_io(png, f);
    png_set_IHDR(png, info, m.cols, m.rows, m.depth() == CV_16U ? 16 : 8, m.channels() == 4 ? PNG_COLOR_TYPE_RGBA : PNG_COLOR_TYPE_GRAY,
                 PNG_INTERLACE_ADAM7, PNG_COMPRESSION_TYPE_DEFAULT, PNG_FILTER_TYPE_DEFAULT);
    png_set_rows(png, info, rows.data());
    png_write_png(png, info, PNG_TRANSFORM_BGR | (m.depth() == CV_16U ? PNG_TRANSFORM_SWAP_ENDIAN : 0), nullptr);
    png_destroy_write_struct(&png, &info);
    ASSERT_EQ(std::fclose(f), 0) << path;
}

// PNGs of every colour type and depth (alpha with holes, values equal to the nodata levels; grey and
// RGBA interlaced too) written into `dir`, and the real maps of TRN_SHARED_DATA when present, each
// checked with and without nodata.
inline void check_validity_cases(const std::string& dir) {
    const std::vector<std::pair<const char*, int>> kinds = {{"v_grey8", CV_8UC1},  {"v_grey16", CV_16UC1}, {"v_rgb8", CV_8UC3},
                                                            {"v_rgba8", CV_8UC4},  {"v_rgba16", CV_16UC4}};
    unsigned seed = 1;
    std::vector<std::string> files;
    for (const auto& [name, type] : kinds) {
        cv::Mat m(29, 41, type);
        cv::RNG rng(seed++);
        rng.fill(m, cv::RNG::UNIFORM, 0, CV_MAT_DEPTH(type) == CV_16U ? 65536 : 256);
        const double top = CV_MAT_DEPTH(type) == CV_16U ? 65535 : 255;
        m(cv::Rect(0, 0, 10, 10)).setTo(cv::Scalar::all(top));  // every channel (alpha too) at the top level
        m(cv::Rect(12, 5, 6, 6)).setTo(cv::Scalar::all(0));      // every channel (alpha too) 0
        const std::string path = dir + "/" + name + ".png";
        ASSERT_TRUE(cv::imwrite(path, m));
        files.push_back(path);
        if (m.channels() == 1 || m.channels() == 4) {
            write_interlaced_png(dir + "/" + name + "_adam7.png", m);
            files.push_back(dir + "/" + name + "_adam7.png");
        }
    }
    for (const char* f : {"realflight2/orthomosaic.png", "realflight3/map.png", "orthophoto.png"})
        if (const std::string p = shared_data(f); !p.empty()) files.push_back(p);
    for (const std::string& f : files)
        for (const std::optional<int> nodata : {std::optional<int>(), std::optional<int>(0), std::optional<int>(255), std::optional<int>(77)})
            expect_validity_as_reference(f, nodata);
    try {
        load_validity(files[0], 256);
        ADD_FAILURE() << "nodata 256 accepted";
    } catch (const Error& e) {
        EXPECT_NE(std::string(e.what()).find("no-data value 256 is not an 8-bit grey level"), std::string::npos) << e.what();
    }
}

}  // namespace trn::test
