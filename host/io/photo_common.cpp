#include "photo_common.hpp"

#include <cmath>
#include <cstdint>

#include "trn/error.hpp"
#include "trn/io/input_file.hpp"

namespace trn::io::detail {
namespace {

bool starts(std::string_view b, std::string_view magic) { return b.substr(0, magic.size()) == magic; }

// Days from 1970-01-01 to y-m-d in the proleptic Gregorian calendar (H. Hinnant's days_from_civil).
std::int64_t days_from_civil(std::int64_t y, unsigned m, unsigned d) {
    y -= m <= 2;
    const std::int64_t era = (y >= 0 ? y : y - 399) / 400;
    const unsigned yoe = static_cast<unsigned>(y - era * 400);
    const unsigned doy = (153 * (m + (m > 2 ? -3 : 9)) + 2) / 5 + d - 1;
    const unsigned doe = yoe * 365 + yoe / 4 - yoe / 100 + doy;
    return era * 146097 + static_cast<std::int64_t>(doe) - 719468;
}

bool leap(int y) { return (y % 4 == 0 && y % 100 != 0) || y % 400 == 0; }

}  // namespace

std::string not_jpeg(std::string_view b) {
    if (b.empty()) return "empty file, not a JPEG";
    if (starts(b, "\xFF\xD8\xFF")) return "";
    const char* what = starts(b, "\x89PNG") ? "a PNG image"
                       : starts(b, "II*\0") || starts(b, "MM\0*") ? "a TIFF (or camera raw) image"
                       : starts(b, "GIF8") ? "a GIF image"
                       : starts(b, "BM") ? "a BMP image"
                       : b.size() >= 12 && b.substr(4, 4) == "ftyp" ? "an ISO media file (HEIC/AVIF photo or video)"
                       : starts(b, "RIFF") ? "a RIFF file (WebP, AVI, WAV)"
                                           : "of an unknown kind";
    return std::string("not a JPEG (the file is ") + what + "); import-photos reads JPEG photos with EXIF";
}

double exif_time_s(const std::string& t, const std::string& subsec, const std::string& name) {
    const auto bad = [&](const std::string& why) {
        return Error(name + ": EXIF DateTimeOriginal '" + quote_input(t, 40) + "' " + why + " (expected YYYY:MM:DD HH:MM:SS)");
    };
    if (t.find_first_not_of(" :0") == std::string::npos) return NAN;  // blank or zeros: "unknown" in EXIF
    if (t.size() != 19) throw bad("is not a date and time");
    int v[6];
    const int at[6] = {0, 5, 8, 11, 14, 17}, len[6] = {4, 2, 2, 2, 2, 2};
    for (int i = 0; i < 6; ++i) {
        v[i] = 0;
        for (int k = 0; k < len[i]; ++k) {
            const char c = t[at[i] + k];
            if (c < '0' || c > '9') throw bad("is not a date and time");
            v[i] = v[i] * 10 + (c - '0');
        }
    }
    if (t[4] != ':' || t[7] != ':' || t[10] != ' ' || t[13] != ':' || t[16] != ':') throw bad("is not a date and time");
    static const int mdays[12] = {31, 28, 31, 30, 31, 30, 31, 31, 30, 31, 30, 31};
    if (v[1] < 1 || v[1] > 12 || v[2] < 1 || v[2] > mdays[v[1] - 1] + (v[1] == 2 && leap(v[0])) || v[3] > 23 || v[4] > 59 || v[5] > 60)
        throw bad("is no calendar date and time");
    double frac = 0;
    if (!subsec.empty()) {
        double scale = 0.1;
        for (char c : subsec) {
            if (c < '0' || c > '9')
                throw Error(name + ": EXIF SubSecTimeOriginal '" + quote_input(subsec, 20) + "' is not digits");
            frac += (c - '0') * scale, scale /= 10;
        }
    }
    return double(days_from_civil(v[0], unsigned(v[1]), unsigned(v[2]))) * 86400 + v[3] * 3600 + v[4] * 60 + v[5] + frac;
}

double focal_plane_sensor_width_mm(double resolution, long unit, double recorded_px, double stored_px) {
    double mm_per_unit = 0;
    switch (unit) {
        case 2: mm_per_unit = 25.4; break;
        case 3: mm_per_unit = 10; break;
        case 4: mm_per_unit = 1; break;
        case 5: mm_per_unit = 0.001; break;
        default: return NAN;
    }
    const double px = recorded_px > 0 ? recorded_px : stored_px;
    if (!(resolution > 0) || !std::isfinite(resolution) || !(px > 0)) return NAN;
    const double mm = px / resolution * mm_per_unit;
    return mm >= 1 && mm <= 100 ? mm : NAN;
}

}  // namespace trn::io::detail
