// Camera photos through exiv2 (EXIF) and OpenCV (JPEG decoding, area reduction, grey).
#include <exiv2/exiv2.hpp>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include <cctype>
#include <cstdint>
#include <cstdio>
#include <mutex>
#include <vector>

#include "photo_common.hpp"
#include "trn/error.hpp"
#include "trn/image.hpp"
#include "trn/io/image_header.hpp"
#include "trn/io/input_file.hpp"
#include "trn/io/photo.hpp"

namespace trn::io {
namespace {

std::string trimmed(std::string s) {
    while (!s.empty() && (s.back() == '\0' || std::isspace(static_cast<unsigned char>(s.back())))) s.pop_back();
    std::size_t b = 0;
    while (b < s.size() && std::isspace(static_cast<unsigned char>(s[b]))) ++b;
    return s.substr(b);
}

// One tag, or nullptr when absent.
const Exiv2::Exifdatum* find(const Exiv2::ExifData& exif, const char* key) {
    const auto it = exif.findKey(Exiv2::ExifKey(key));
    return it == exif.end() ? nullptr : &*it;
}

std::string tag_name(const char* key) {
    const std::string k = key;
    return k.substr(k.find_last_of('.') + 1);
}

// The first value of an integer tag. exiv2 0.28 (Debian 13) renamed toLong(long) to toInt64(size_t).
std::int64_t first_integer(const Exiv2::Exifdatum& d) {
#if EXIV2_TEST_VERSION(0, 28, 0)
    return d.toInt64(0);
#else
    return d.toLong(0);
#endif
}

// Value i of a rational tag as a double; a zero denominator or a tag of another type names the tag.
double rational(const Exiv2::Exifdatum& d, std::size_t i, const std::string& name, const char* key) {
    const Exiv2::TypeId t = d.typeId();
    if (t != Exiv2::unsignedRational && t != Exiv2::signedRational)
        throw Error(name + ": EXIF " + tag_name(key) + " is of type " + (Exiv2::TypeInfo::typeName(t) ? Exiv2::TypeInfo::typeName(t) : "?") +
                    ", not a rational number");
    if (static_cast<std::size_t>(d.count()) <= i)  // count(): long in exiv2 0.27, size_t in 0.28
        throw Error(name + ": EXIF " + tag_name(key) + " has " + std::to_string(d.count()) + " values, expected at least " + std::to_string(i + 1));
    const Exiv2::Rational r = d.toRational(i);
    if (r.second == 0) throw Error(name + ": EXIF " + tag_name(key) + " has a zero denominator (" + std::to_string(r.first) + "/0)");
    return double(r.first) / double(r.second);
}

// GPSLatitude / GPSLongitude: degrees, minutes, seconds with their N/S or E/W reference.
std::optional<double> coordinate(const Exiv2::ExifData& exif, const char* key, const char* ref_key, const char* positive,
                                 const char* negative, double limit, const std::string& name) {
    const Exiv2::Exifdatum* d = find(exif, key);
    const Exiv2::Exifdatum* ref = find(exif, ref_key);
    if (!d && !ref) return std::nullopt;
    if (!d) throw Error(name + ": EXIF " + tag_name(ref_key) + " without " + tag_name(key));
    if (!ref) throw Error(name + ": EXIF " + tag_name(key) + " without " + tag_name(ref_key) + " (" + positive + " or " + negative + ")");
    if (d->count() != 3)
        throw Error(name + ": EXIF " + tag_name(key) + " has " + std::to_string(d->count()) + " values, expected 3 (degrees, minutes, seconds)");
    const double deg = rational(*d, 0, name, key), min = rational(*d, 1, name, key), sec = rational(*d, 2, name, key);
    if (deg < 0 || min < 0 || min > 60 || sec < 0 || sec > 60)  // 60 itself: a writer's rounding
        throw Error(name + ": EXIF " + tag_name(key) + " " + quote_input(d->toString()) + " is not degrees, minutes (<= 60) and seconds (<= 60)");
    const double v = deg + min / 60 + sec / 3600;
    if (v > limit) {
        char text[64];
        std::snprintf(text, sizeof text, " %.6g deg is beyond %g", v, limit);
        throw Error(name + ": EXIF " + tag_name(key) + text);
    }
    const std::string r = trimmed(ref->toString());
    if (r == positive) return v;
    if (r == negative) return -v;
    throw Error(name + ": EXIF " + tag_name(ref_key) + " '" + quote_input(r, 20) + "' is neither " + positive + " nor " + negative);
}

void mute_exiv2_once() {
    static std::once_flag once;
    std::call_once(once, [] {
        Exiv2::LogMsg::setLevel(Exiv2::LogMsg::mute);  // its warnings are not ours to print; errors come as exceptions
        Exiv2::XmpParser::initialize();                 // not thread-safe on first use: done once here
    });
}

}  // namespace

PhotoExif parse_photo_exif(std::string_view bytes, const std::string& name) {
    if (const std::string why = detail::not_jpeg(bytes); !why.empty()) throw Error(name + ": " + why);
    mute_exiv2_once();
    PhotoExif p;
    // The image keeps its ExifData: only references to it here, so no exiv2 container is
    // instantiated in this file (its weak symbols would be exported beside our API, and the device
    // kit's io layer must export exactly the same).
    // exiv2 0.27 hands the image over as Image::AutoPtr, a std::auto_ptr (deprecated), 0.28 as
    // Image::UniquePtr: taken by auto, never named here (and Clang's -Wdeprecated-declarations has
    // nothing to report).
    auto image = [&] {
        try {
            auto opened =
                Exiv2::ImageFactory::open(reinterpret_cast<const Exiv2::byte*>(bytes.data()), static_cast<long>(bytes.size()));
            if (!opened.get()) throw Error(name + ": not a JPEG exiv2 can read");
            opened->readMetadata();
            return opened;
        } catch (const Error&) {
            throw;
        } catch (const std::bad_alloc&) {
            throw Error(name + ": corrupt JPEG or EXIF (exiv2 ran out of memory reading it)");
        } catch (const std::exception& e) {  // Exiv2::AnyError, and what its parsers let escape (std::out_of_range ...)
            throw Error(name + ": corrupt JPEG or EXIF (exiv2: " + quote_input(e.what(), 120) + ")");
        }
    }();
    p.width = image->pixelWidth(), p.height = image->pixelHeight();
    if (p.width <= 0 || p.height <= 0) throw Error(name + ": corrupt JPEG (no image size in its frame header)");
    const Exiv2::ExifData& exif = image->exifData();
    try {
        if (const auto* d = find(exif, "Exif.Image.Make")) p.make = trimmed(d->toString());
        if (const auto* d = find(exif, "Exif.Image.Model")) p.model = trimmed(d->toString());
        if (const auto* d = find(exif, "Exif.Photo.DateTimeOriginal")) {
            p.datetime_original = trimmed(d->toString());
            std::string subsec;
            if (const auto* s = find(exif, "Exif.Photo.SubSecTimeOriginal")) subsec = trimmed(s->toString());
            p.time_s = detail::exif_time_s(p.datetime_original, subsec, name);  // NaN: the blank "unknown" date
            if (std::isnan(p.time_s)) p.datetime_original.clear();
        }
        if (const auto* d = find(exif, "Exif.Photo.FocalLength")) {
            p.focal_length_mm = rational(*d, 0, name, "Exif.Photo.FocalLength");
            if (!(p.focal_length_mm > 0 && p.focal_length_mm < 10000))
                throw Error(name + ": EXIF FocalLength " + quote_input(d->toString()) + " is not a focal length in mm");
        }
        if (const auto* d = find(exif, "Exif.Photo.FocalPlaneXResolution"); d && d->count() >= 1 &&
            (d->typeId() == Exiv2::unsignedRational || d->typeId() == Exiv2::signedRational) && d->toRational(0).second != 0) {
            const auto* unit = find(exif, "Exif.Photo.FocalPlaneResolutionUnit");
            const auto* recorded = find(exif, "Exif.Photo.PixelXDimension");
            p.sensor_width_mm = detail::focal_plane_sensor_width_mm(
                rational(*d, 0, name, "Exif.Photo.FocalPlaneXResolution"), unit && unit->count() == 1 ? first_integer(*unit) : 2,
                recorded && recorded->count() == 1 ? double(first_integer(*recorded)) : 0, p.width);
        }
        if (const auto* d = find(exif, "Exif.Image.Orientation")) {
            const std::int64_t o = d->count() == 1 ? first_integer(*d) : -1;
            if (o < 1 || o > 8) throw Error(name + ": EXIF Orientation " + quote_input(d->toString()) + " is not one of 1..8");
            p.orientation = static_cast<int>(o);
        }
        const auto lat = coordinate(exif, "Exif.GPSInfo.GPSLatitude", "Exif.GPSInfo.GPSLatitudeRef", "N", "S", 90, name);
        const auto lon = coordinate(exif, "Exif.GPSInfo.GPSLongitude", "Exif.GPSInfo.GPSLongitudeRef", "E", "W", 180, name);
        if (lat.has_value() != lon.has_value())
            throw Error(name + ": EXIF " + (lat ? "GPSLatitude without GPSLongitude" : "GPSLongitude without GPSLatitude"));
        const auto* status = find(exif, "Exif.GPSInfo.GPSStatus");
        const bool void_fix = status && trimmed(status->toString()) == "V";  // "measurement void": the receiver had no fix
        if (lat && !void_fix) {
            p.gps = GpsFix{*lat, *lon, NAN};
            if (const auto* a = find(exif, "Exif.GPSInfo.GPSAltitude")) {
                const double alt = rational(*a, 0, name, "Exif.GPSInfo.GPSAltitude");
                const auto* ref = find(exif, "Exif.GPSInfo.GPSAltitudeRef");
                p.gps->altitude_m = ref && ref->count() == 1 && first_integer(*ref) == 1 ? -alt : alt;
            }
        }
    } catch (const Error&) {
        throw;
    } catch (const std::exception& e) {
        throw Error(name + ": corrupt EXIF (exiv2: " + quote_input(e.what(), 120) + ")");
    }
    return p;
}

PhotoExif read_photo_exif(const std::string& path) { return parse_photo_exif(read_input_file(path, kMaxPhotoFileBytes, "a photo"), path); }

GrayImage load_photo_gray(const std::string& path, int width) {
    if (width < 2) throw Error(path + ": a frame width of " + std::to_string(width) + " px is too small");
    const std::string bytes = read_input_file(path, kMaxPhotoFileBytes, "a photo");
    if (const std::string why = detail::not_jpeg(bytes); !why.empty()) throw Error(path + ": " + why);
    const ImageSize size = check_image_file(path);  // the header's size against trnkit's limits before any pixel memory
    // Decoded at 1/8, 1/4 or 1/2 scale in the DCT domain (libjpeg's scaled IDCT: each pixel the
    // mean of an 8x8, 4x4 or 2x2 block, itself an area average) when that is still at least `width`
    // wide: 60x less to decode for a 4000 px photo, and the way realflight2's frames were made.
    int reduce = 1;
    while (reduce < 8 && (size.width + 2 * reduce - 1) / (2 * reduce) >= width) reduce *= 2;
    const int flag = reduce == 8 ? cv::IMREAD_REDUCED_COLOR_8 : reduce == 4 ? cv::IMREAD_REDUCED_COLOR_4 : reduce == 2 ? cv::IMREAD_REDUCED_COLOR_2 : cv::IMREAD_COLOR;
    cv::Mat colour;
    try {
        const cv::Mat raw(1, static_cast<int>(bytes.size()), CV_8UC1, const_cast<char*>(bytes.data()));
        colour = cv::imdecode(raw, flag | cv::IMREAD_IGNORE_ORIENTATION);
    } catch (const cv::Exception& e) {
        throw Error(path + ": cannot decode the JPEG (" + e.msg + ")");
    }
    if (colour.empty()) throw Error(path + ": corrupt JPEG (OpenCV cannot decode it)");
    cv::Mat reduced = colour;
    if (width < size.width) {  // the height in proportion to the photo's own size, not the scaled decode's
        const int height = std::max(1, static_cast<int>(std::lround(double(size.height) * width / size.width)));
        cv::resize(colour, reduced, cv::Size(width, height), 0, 0, cv::INTER_AREA);
    }
    cv::Mat grey;
    cv::cvtColor(reduced, grey, cv::COLOR_BGR2GRAY);
    GrayImage img{grey.cols, grey.rows, std::vector<std::uint8_t>(std::size_t(grey.cols) * grey.rows)};
    for (int y = 0; y < grey.rows; ++y) std::copy_n(grey.ptr<std::uint8_t>(y), grey.cols, img.pixels.data() + std::size_t(y) * grey.cols);
    return img;
}

std::string photo_reader_name() { return std::string("exiv2 ") + Exiv2::versionString(); }

}  // namespace trn::io
