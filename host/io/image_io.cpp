#include "trn/io/image_io.hpp"

#include <filesystem>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include "trn/error.hpp"
#include "trn/io/atomic_file.hpp"
#include "trn/io/image_header.hpp"
#include "trn/limits.hpp"

namespace trn {

GrayImage load_gray(const std::string& path) {
    // A regular file in a format whose header trnkit reads, its sides, pixels and decode cost
    // within the limits, before OpenCV allocates anything (image_header.hpp).
    check_image_file(path);
    const std::string what = path + ": image";
    cv::Mat m;
    try {
        m = cv::imread(path, cv::IMREAD_GRAYSCALE);
    } catch (const cv::Exception& e) {
        throw Error(path + ": cannot decode image (" + e.msg + ")");
    }
    if (m.empty()) throw Error(path + ": not a readable image (corrupt or unsupported format)");
    limits::check_image(what, m.cols, m.rows, limits::kMaxMapPixels, limits::kLoadBytesPerPixel);
    GrayImage img{m.cols, m.rows, std::vector<std::uint8_t>(std::size_t(m.cols) * m.rows)};
    for (int y = 0; y < m.rows; ++y) std::copy_n(m.ptr<std::uint8_t>(y), m.cols, img.pixels.data() + std::size_t(y) * m.cols);
    return img;
}

// Encoded in memory (format from the extension), then written whole: a full disk or a killed run
// never leaves a cut image under the final name.
void save_gray(const std::string& path, GrayView image) {
    const std::string ext = std::filesystem::path(path).extension().string();
    if (ext.empty()) throw Error(path + ": no image extension (.png, .jpg, .tif, ...)");
    const cv::Mat m(image.height, image.width, CV_8UC1, const_cast<std::uint8_t*>(image.data), image.stride);
    std::vector<uchar> bytes;
    bool ok = false;
    try {
        ok = cv::imencode(ext, m, bytes);
    } catch (const cv::Exception& e) {
        throw Error(path + ": cannot encode image (" + e.msg + ")");
    }
    if (!ok) throw Error(path + ": cannot encode image as " + ext);
    io::write_file_atomic(path, std::string_view(reinterpret_cast<const char*>(bytes.data()), bytes.size()));
}

void save_gradient(const std::string& path, ImageView<const std::int16_t> g) {
    const cv::Mat src(g.height, g.width, CV_16SC1, const_cast<std::int16_t*>(g.data), g.stride * sizeof(std::int16_t));
    cv::Mat out;
    src.convertTo(out, CV_8UC1, 1.0 / 8.0, 128.0);
    save_gray(path, {out.data, out.cols, out.rows, static_cast<std::ptrdiff_t>(out.step)});
}

}  // namespace trn
