#pragma once
// Camera photos for the import tests: JPEGs made with OpenCV, their EXIF written with exiv2 (what a
// camera writes, or deliberately not: missing tags, odd orientations, broken values).
#include <exiv2/exiv2.hpp>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include <cmath>
#include <cstdint>
#include <cstdio>
#include <map>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

namespace trn::test {

// EXIF keys -> values as exiv2 parses them for the tag's type ("" removes the tag).
struct TestExif {
    std::map<std::string, std::string> tags = {
        {"Exif.Image.Make", "Canon"},
        {"Exif.Image.Model", "Canon PowerShot SX260 HS"},
        {"Exif.Image.Orientation", "1"},
        {"Exif.Photo.DateTimeOriginal", "2014:10:19 13:21:56"},
        {"Exif.Photo.FocalLength", "4500/1000"},
        {"Exif.GPSInfo.GPSLatitudeRef", "N"},
        {"Exif.GPSInfo.GPSLatitude", "30/1 10/1 14904/1000"},
        {"Exif.GPSInfo.GPSLongitudeRef", "W"},
        {"Exif.GPSInfo.GPSLongitude", "98/1 5/1 22308/1000"},
        {"Exif.GPSInfo.GPSAltitudeRef", "0"},
        {"Exif.GPSInfo.GPSAltitude", "3805/10"},
    };
    TestExif& set(const std::string& key, const std::string& value) {
        tags[key] = value;
        return *this;
    }
    TestExif& remove(const std::string& key) { return set(key, ""); }
    // Latitude / longitude in signed degrees as GPS rationals with their references.
    TestExif& gps(double lat, double lon) {
        auto dms = [](double v) {  // in whole micro-arcseconds, so the seconds never round up to 60
            const long long t = std::llround(std::fabs(v) * 3600e6);
            const long long d = t / 3600'000000, m = t / 60'000000 % 60, s = t % 60'000000;
            return std::to_string(d) + "/1 " + std::to_string(m) + "/1 " + std::to_string(s) + "/1000000";
        };
        set("Exif.GPSInfo.GPSLatitudeRef", lat < 0 ? "S" : "N").set("Exif.GPSInfo.GPSLatitude", dms(lat));
        return set("Exif.GPSInfo.GPSLongitudeRef", lon < 0 ? "W" : "E").set("Exif.GPSInfo.GPSLongitude", dms(lon));
    }
};

// A BGR image with texture (blocks and a gradient), w x h.
inline cv::Mat test_picture(int w, int h, std::uint32_t seed) {
    cv::Mat m(h, w, CV_8UC3);
    std::uint32_t s = seed * 2654435761u + 1;
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
            const int bx = x / 16, by = y / 16;
            std::uint32_t v = (bx * 73856093u) ^ (by * 19349663u) ^ s;
            v ^= v >> 13, v *= 0x5bd1e995u, v ^= v >> 15;
            m.at<cv::Vec3b>(y, x) = cv::Vec3b(static_cast<std::uint8_t>(v), static_cast<std::uint8_t>(v >> 8),
                                              static_cast<std::uint8_t>((x * 255) / std::max(1, w - 1)));
        }
    return m;
}

// Writes `picture` as a JPEG (quality 95) with exactly the tags of `exif`.
inline void write_test_photo(const std::string& path, const cv::Mat& picture, const TestExif& exif) {
    std::vector<std::uint8_t> bytes;
    if (!cv::imencode(".jpg", picture, bytes, {cv::IMWRITE_JPEG_QUALITY, 95})) throw std::runtime_error("imencode failed");
    FILE* f = std::fopen(path.c_str(), "wb");
    if (!f || std::fwrite(bytes.data(), 1, bytes.size(), f) != bytes.size() || std::fclose(f) != 0) throw std::runtime_error(path);
    auto image = Exiv2::ImageFactory::open(path);
    Exiv2::ExifData data;
    for (const auto& [k, v] : exif.tags)
        if (!v.empty()) data[k] = v;
    image->setExifData(data);
    image->writeMetadata();
}

}  // namespace trn::test
