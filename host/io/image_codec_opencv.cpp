// Image files through OpenCV's imgcodecs: every format OpenCV was built with.
#include <opencv2/imgcodecs.hpp>

#include "image_codec.hpp"
#include "trn/error.hpp"

namespace trn::io::detail {

namespace {
// cv::imread with its failures as trn::Error naming the file.
cv::Mat read(const std::string& path, int flags) {
    cv::Mat m;
    try {
        m = cv::imread(path, flags);
    } catch (const cv::Exception& e) {
        throw Error(path + ": cannot decode image (" + e.msg + ")");
    }
    if (m.empty()) throw Error(path + ": not a readable image (corrupt or unsupported format)");
    return m;
}
}  // namespace

GrayImage decode_gray(const std::string& path) {
    const cv::Mat m = read(path, cv::IMREAD_GRAYSCALE);
    GrayImage img{m.cols, m.rows, std::vector<std::uint8_t>(std::size_t(m.cols) * m.rows)};
    for (int y = 0; y < m.rows; ++y) std::copy_n(m.ptr<std::uint8_t>(y), m.cols, img.pixels.data() + std::size_t(y) * m.cols);
    return img;
}

namespace {
// The high byte of every 16-bit sample, as libpng's strip_16 and IMREAD_GRAYSCALE keep it.
cv::Mat high_bytes(const cv::Mat& m) {
    cv::Mat out(m.rows, m.cols, CV_MAKETYPE(CV_8U, m.channels()));
    for (int y = 0; y < m.rows; ++y) {
        const std::uint16_t* in = m.ptr<std::uint16_t>(y);
        std::uint8_t* o = out.ptr<std::uint8_t>(y);
        for (int i = 0; i < m.cols * m.channels(); ++i) o[i] = static_cast<std::uint8_t>(in[i] >> 8);
    }
    return out;
}
}  // namespace

GrayImage decode_validity(const std::string& path, std::optional<int> nodata) {
    cv::Mat m = read(path, cv::IMREAD_UNCHANGED);
    if (m.depth() == CV_16U) m = high_bytes(m);
    if (m.depth() != CV_8U) throw Error(path + ": no-data needs 8- or 16-bit pixels");
    const int channels = m.channels();
    const bool alpha = channels == 2 || channels == 4;
    const int colours = alpha ? channels - 1 : channels;
    if (!alpha && !nodata) return {};
    GrayImage valid{m.cols, m.rows, std::vector<std::uint8_t>(std::size_t(m.cols) * m.rows, 255)};
    for (int y = 0; y < m.rows; ++y) {
        const std::uint8_t* p = m.ptr<std::uint8_t>(y);
        std::uint8_t* out = valid.pixels.data() + std::size_t(y) * m.cols;
        for (int x = 0; x < m.cols; ++x, p += channels) {
            bool no_data = alpha && p[channels - 1] == 0;
            if (nodata && !no_data) {
                no_data = true;
                for (int c = 0; c < colours; ++c) no_data = no_data && p[c] == *nodata;
            }
            if (no_data) out[x] = 0;
        }
    }
    return valid;
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
