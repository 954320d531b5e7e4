// Fuzz entry: a set of camera photos' EXIF as import-photos checks it (host/sim/photo_import.cpp,
// check_photo_set over parse_photo_exif). The input is one or more JPEGs back to back (split at
// each start of image, FF D8 FF). A refusal must be trn::Error; a set it accepts is one camera at
// one focal length and one size, in time order from 0, at most 1000 photos/s, with a finite field
// of view.
#include <cmath>
#include <string>
#include <string_view>
#include <vector>

#include "fuzz_check.hpp"
#include "trn/error.hpp"
#include "trn/io/photo.hpp"
#include "trn/sim/photo_import.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    using trn::fuzz::require;
    const std::string_view all = trn::fuzz::as_text(data, size);
    std::vector<std::string_view> jpegs;
    for (std::size_t at = 0; at < all.size() && jpegs.size() < 8;) {
        const std::size_t next = all.find("\xFF\xD8\xFF", at + 1);
        jpegs.push_back(all.substr(at, next == std::string_view::npos ? std::string_view::npos : next - at));
        at = next == std::string_view::npos ? all.size() : next;
    }
    trn::sim::PhotoImportOptions o;
    o.photos = "fuzz";
    o.altitude_agl_m = 50;
    o.sensor_width_mm = size % 2 ? 6.17 : 0;  // given, or from the table / EXIF
    o.ignore_orientation = size % 3 == 0;
    std::vector<trn::sim::ImportedPhoto> photos;
    trn::sim::PhotoImportResult r;
    try {
        for (std::size_t i = 0; i < jpegs.size(); ++i) {
            trn::sim::ImportedPhoto p;
            p.photo = "p" + std::to_string(i) + ".jpg";
            p.exif = trn::io::parse_photo_exif(std::string(jpegs[i]), p.photo);
            photos.push_back(std::move(p));
        }
        r = trn::sim::check_photo_set(photos, o);
    } catch (const trn::Error&) {
        return 0;
    }
    require(r.photos.size() == photos.size() && !r.photos.empty(), "photos lost or gained");
    require(r.photos.front().time_s == 0, "the first photo's time is not 0");
    for (std::size_t i = 0; i < r.photos.size(); ++i) {
        const trn::io::PhotoExif& e = r.photos[i].exif;
        const trn::io::PhotoExif& f = r.photos.front().exif;
        require(e.model == f.model && e.make == f.make, "two cameras accepted in one set");
        require(e.width == f.width && e.height == f.height, "two photo sizes accepted in one set");
        if (i) require(r.photos[i].time_s >= r.photos[i - 1].time_s, "photos not in time order");
        require(o.ignore_orientation || e.orientation <= 1, "a rotated photo accepted without ignore_orientation");
    }
    require(r.fps > 0 && r.fps <= 1000, "a photo rate outside (0, 1000] accepted");
    require(std::isfinite(r.hfov_deg) && r.hfov_deg > 0 && r.hfov_deg < 180, "a field of view outside (0, 180) deg");
    require(r.gps_fixes <= r.photos.size(), "more GPS fixes than photos");
    return 0;
}
