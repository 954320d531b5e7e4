// Image files through OpenCV's imgcodecs: every format OpenCV was built with.
#include <opencv2/imgcodecs.hpp>

#include "image_codec.hpp"
#include "trn/error.hpp"

namespace trn::io::detail {

GrayImage decode_gray(const std::string& path) {
    cv::Mat m;
    try {
        m = cv::imread(path, cv::IMREAD_GRAYSCALE);
    } catch (const cv::Exception& e) {
        throw Error(path + ": cannot decode image (" + e.msg + ")");
    }
    if (m.empty()) throw Error(path + ": not a readable image (corrupt or unsupported format)");
    GrayImage img{m.cols, m.rows, std::vector<std::uint8_t>(std::size_t(m.cols) * m.rows)};
    for (int y = 0; y < m.rows; ++y) std::copy_n(m.ptr<std::uint8_t>(y), m.cols, img.pixels.data() + std::size_t(y) * m.cols);
    return img;
}

std::vector<std::uint8_t> encode_gray(const std::string& path, const std::string& extension, GrayView image) {
    const cv::Mat m(image.height, image.width, CV_8UC1, const_cast<std::uint8_t*>(image.data), image.stride);
    std::vector<uchar> bytes;
    bool ok = false;
    try {
        ok = cv::imencode(extension, m, bytes);
    } catch (const cv::Exception& e) {
        throw Error(path + ": cannot encode image (" + e.msg + ")");
    }
    if (!ok) throw Error(path + ": cannot encode image as " + extension);
    return bytes;
}

const char* image_codec_name() { return "OpenCV imgcodecs"; }

}  // namespace trn::io::detail
