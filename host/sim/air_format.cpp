#include "trn/sim/air_format.hpp"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <istream>
#include <limits>
#include <nlohmann/json.hpp>
#include <utility>

#include "trn/error.hpp"
#include "trn/io/atomic_file.hpp"
#include "trn/io/outside_text.hpp"
#include "trn/io/input_file.hpp"
#include "trn/io/provenance.hpp"
#include "trn/detail/angles.hpp"
#include "trn/sim/geodesy.hpp"

namespace trn::sim {
namespace {

// The 20 columns in writer order; numeric_field(i) is where column i goes.
const std::vector<std::string> kColumns = {
    "Filename", "Latitude", "Longitude", "RelativeAltitude", "ImuX", "ImuY", "ImuZ", "ImuW", "PoseX", "PoseY", "PoseZ",
    "OrientationX", "OrientationY", "OrientationZ", "OrientationW", "MapX", "MapY", "SvoX", "SvoY", "SvoZ"};

double* numeric_field(AirRecord& r, std::size_t i) {
    double* fields[] = {nullptr, &r.latitude_deg, &r.longitude_deg, &r.relative_altitude_m, &r.imu.x, &r.imu.y,
                        &r.imu.z, &r.imu.w, &r.pose_m.x, &r.pose_m.y, &r.pose_m.z, &r.orientation.x, &r.orientation.y,
                        &r.orientation.z, &r.orientation.w, &r.map_x, &r.map_y, &r.svo_m.x, &r.svo_m.y, &r.svo_m.z};
    return fields[i];
}

// Columns a flight may lack, each group as a whole (kColumns indices, first..last).
struct ColumnGroup {
    std::size_t first, last;
    const char* name;
};
constexpr ColumnGroup kOptionalGroups[] = {
    {1, 2, "Latitude,Longitude"}, {4, 7, "ImuX..ImuW"},           {8, 10, "PoseX..PoseZ"},
    {11, 14, "OrientationX..OrientationW"}, {15, 16, "MapX,MapY"}, {17, 19, "SvoX..SvoZ"}};

const ColumnGroup* group_of(std::size_t c) {
    for (const ColumnGroup& g : kOptionalGroups)
        if (c >= g.first && c <= g.last) return &g;
    return nullptr;
}

std::string trim(std::string_view s) {
    const auto b = s.find_first_not_of(" \t\r");
    if (b == std::string_view::npos) return {};
    return std::string(s.substr(b, s.find_last_not_of(" \t\r") - b + 1));
}

bool group_empty(const ColumnGroup& g, const std::vector<std::string>& fields, const std::vector<int>& column_of) {
    for (std::size_t c = g.first; c <= g.last; ++c)
        if (!fields[column_of[c]].empty()) return false;
    return true;
}

// Splits one CSV line; fields may be double-quoted with "" for a quote inside. False when a quote
// is left open or text follows a closing quote.
bool split_csv(const std::string& line, std::vector<std::string>& out, std::string& why) {
    out.clear();
    std::size_t i = 0;
    const std::size_t n = line.size();
    while (true) {
        while (i < n && (line[i] == ' ' || line[i] == '\t')) ++i;
        std::string field;
        if (i < n && line[i] == '"') {
            ++i;
            bool closed = false;
            while (i < n) {
                if (line[i] == '"') {
                    if (i + 1 < n && line[i + 1] == '"') {
                        field += '"', i += 2;
                        continue;
                    }
                    closed = true, ++i;
                    break;
                }
                field += line[i++];
            }
            if (!closed) return why = "unterminated quoted field", false;
            while (i < n && (line[i] == ' ' || line[i] == '\t' || line[i] == '\r')) ++i;
            if (i < n && line[i] != ',') return why = "text after a closing quote", false;
            out.push_back(field);
        } else {
            const std::size_t e = line.find(',', i);
            out.push_back(trim(std::string_view(line).substr(i, e == std::string::npos ? std::string::npos : e - i)));
            i = e == std::string::npos ? n : e;
        }
        if (i >= n) break;
        ++i;  // the comma
    }
    return true;
}

// Plausible magnitudes, far beyond any real flight but small enough that arithmetic on them stays
// meaningful: a MapX of 1e300 is a broken file, not a position.
constexpr double kMaxMetres = 1e7;       // Pose*, Svo*, RelativeAltitude: 10,000 km
constexpr double kMaxMapPixels = 1e7;    // MapX, MapY
constexpr double kMaxAltitudeM = 20000;  // RelativeAltitude: above any UAV
constexpr std::size_t kMaxLineBytes = 64 << 10;  // a metadata.csv row is ~250 bytes
constexpr const char* kTimeColumn = "TimeS";      // optional (air_format.hpp)
constexpr double kMaxTimeS = 1e11;                // Unix seconds for 3000 years, or any flight clock

std::string number_text(double v) {
    char buf[32];
    std::snprintf(buf, sizeof buf, "%.6g", v);
    return buf;
}

// A stream over text already in memory (no copy).
struct ViewBuffer : std::streambuf {
    explicit ViewBuffer(std::string_view s) {
        char* p = const_cast<char*>(s.data());
        setg(p, p, p + s.size());
    }
};

// A JSON value as an error message shows it: at most kMaxQuotedChars of its text.
std::string shown(const nlohmann::json& v) { return io::quote_input(io::json_line(v)); }

// Why value v of column c is implausible ("" when it is fine).
std::string implausible(std::size_t c, double v) {
    const std::string& name = kColumns[c];
    auto outside = [&](double lo, double hi) {
        char buf[160];
        std::snprintf(buf, sizeof buf, " %.6g is outside [%g, %g]", v, lo, hi);
        return name + buf;
    };
    if (name == "Latitude") return v < -90 || v > 90 ? outside(-90, 90) : "";
    if (name == "Longitude") return v < -180 || v > 180 ? outside(-180, 180) : "";
    if (name == "MapX" || name == "MapY") return std::fabs(v) > kMaxMapPixels ? outside(-kMaxMapPixels, kMaxMapPixels) : "";
    if (name.rfind("Imu", 0) == 0 || name.rfind("Orientation", 0) == 0) return "";  // see not_unit
    if (name == "RelativeAltitude" && std::fabs(v) <= kMaxMetres)  // the camera's height gives each frame's scale
        return v > 0 && v <= kMaxAltitudeM ? "" : name + " " + number_text(v) + " m is not a flight altitude (expected (0, 20000] m)";
    return std::fabs(v) > kMaxMetres ? outside(-kMaxMetres, kMaxMetres) : "";
}

// A unit quaternion up to rounding; an all-zero or scaled one has no attitude to read.
std::string not_unit(const Quaternion& q, const char* prefix) {
    const double n = std::sqrt(q.x * q.x + q.y * q.y + q.z * q.z + q.w * q.w);
    if (n > 0.9 && n < 1.1) return "";
    char buf[160];
    std::snprintf(buf, sizeof buf, "%sX,%sY,%sZ,%sW has length %.6g; an attitude quaternion has length 1", prefix, prefix, prefix, prefix, n);
    return buf;
}

// The frame number at the end of a file name's stem ("frame_000012.png" -> "12"), without leading
// zeros, or "" when the stem does not end in digits. Compared by length then text, so numbers of
// any length order correctly without overflow.
std::string trailing_number(const std::string& filename) {
    const std::size_t dot = filename.find_last_of('.');
    const std::size_t slash = filename.find_last_of("/\\");
    const std::size_t end = dot == std::string::npos || (slash != std::string::npos && dot < slash) ? filename.size() : dot;
    std::size_t b = end;
    while (b > 0 && filename[b - 1] >= '0' && filename[b - 1] <= '9') --b;
    if (b == end) return "";
    while (b + 1 < end && filename[b] == '0') ++b;
    return filename.substr(b, end - b);
}

bool number_less_or_equal(const std::string& a, const std::string& b) { return a.size() != b.size() ? a.size() < b.size() : a <= b; }

std::string quote_if_needed(const std::string& s) {
    if (s.find_first_of(",\"\n\r") == std::string::npos && s == trim(s)) return s;
    std::string q = "\"";
    for (char c : s) q += c == '"' ? std::string("\"\"") : std::string(1, c);
    return q + "\"";
}

}  // namespace

Quaternion attitude_quaternion(double heading, double roll, double pitch) {
    // ENU yaw is counter-clockwise from east; body FLU: roll about x (right wing down positive),
    // pitch about y (nose down positive in FLU), so nose up is -pitch about y.
    const double yaw = kPi / 2 - heading;
    const double cy = std::cos(yaw / 2), sy = std::sin(yaw / 2);
    const double cp = std::cos(-pitch / 2), sp = std::sin(-pitch / 2);
    const double cr = std::cos(roll / 2), sr = std::sin(roll / 2);
    return {sr * cp * cy - cr * sp * sy, cr * sp * cy + sr * cp * sy, cr * cp * sy - sr * sp * cy, cr * cp * cy + sr * sp * sy};
}

double heading_from_quaternion(const Quaternion& q) {
    const double yaw = std::atan2(2 * (q.w * q.z + q.x * q.y), 1 - 2 * (q.y * q.y + q.z * q.z));
    return wrap_angle(kPi / 2 - yaw);
}

RollPitch roll_pitch_from_quaternion(const Quaternion& in) {
    if (std::isnan(in.w)) return {0, 0};  // no attitude measured (empty ImuX..W): taken as level
    const double n = std::sqrt(in.x * in.x + in.y * in.y + in.z * in.z + in.w * in.w);  // the reader allows 0.9-1.1
    const Quaternion q{in.x / n, in.y / n, in.z / n, in.w / n};
    // ZYX Euler angles of the quaternion; attitude_quaternion stores nose-up pitch as -pitch.
    const double roll = std::atan2(2 * (q.w * q.x + q.y * q.z), 1 - 2 * (q.x * q.x + q.y * q.y));
    const double sin_p = std::clamp(2 * (q.w * q.y - q.z * q.x), -1.0, 1.0);
    return {roll, -std::asin(sin_p)};
}

double tilt_from_nadir(double roll_rad, double pitch_rad) {
    // The body z axis after pitch then roll has vertical component cos(pitch) cos(roll).
    return std::acos(std::clamp(std::cos(roll_rad) * std::cos(pitch_rad), -1.0, 1.0));
}

AirRecord make_air_record(const FlightFrame& f, const std::string& filename) {
    AirRecord r;
    r.filename = filename;
    r.latitude_deg = f.geo.latitude_deg;
    r.longitude_deg = f.geo.longitude_deg;
    r.relative_altitude_m = f.baro_altitude_m;  // measured (barometer), as on a real flight; PoseZ is the truth
    r.imu = attitude_quaternion(f.magnetometer_heading_rad, f.truth.roll_rad, f.truth.pitch_rad);
    r.pose_m = f.position_m;
    r.orientation = attitude_quaternion(f.truth.yaw_rad, f.truth.roll_rad, f.truth.pitch_rad);
    r.map_x = f.truth.map_x;
    r.map_y = f.truth.map_y;
    r.svo_m = f.odometry_m;
    return r;
}

const std::vector<std::string>& air_columns() { return kColumns; }

// ---- flight.json ----

void write_flight_info(const std::string& path, const FlightInfo& info) {
    nlohmann::json j;
    j["scenario"] = info.scenario;
    j["map_file"] = info.map_file;
    if (info.metres_per_pixel > 0) j["metres_per_pixel"] = info.metres_per_pixel;  // 0: not stated (no map, or a GeoTIFF's own)
    if (info.origin) j["origin"] = {{"latitude_deg", info.origin->latitude_deg}, {"longitude_deg", info.origin->longitude_deg}};
    j["camera"] = {{"width", info.camera.width}, {"height", info.camera.height}, {"hfov_deg", info.camera.hfov_deg}};
    j["fps"] = info.fps;
    j["map_year"] = info.map_year;
    j["rendered_year"] = info.rendered_year;
    j["seed"] = info.seed;
    if (info.frames) j["frames"] = info.frames;
    if (!info.latlon_source.empty()) j["latlon_source"] = info.latlon_source;
    io::add_provenance(j);
    io::write_file_atomic(path, io::json_text(j, 2));
}

namespace {

// An integer field of flight.json within [lo, hi]; a fraction, a string or 1e10 names the field.
int int_field(const nlohmann::json& j, const char* key, int lo, int hi, const std::string& where) {
    const nlohmann::json& v = j.at(key);
    if (!v.is_number_integer() || v.get<long long>() < lo || v.get<long long>() > hi)
        throw Error(where + key + " " + shown(v) + " must be a whole number in [" + std::to_string(lo) + ", " + std::to_string(hi) + "]");
    return static_cast<int>(v.get<long long>());
}

// An unsigned field of flight.json up to hi (absent: 0); 1e300, -1 or 2.5 name the field instead of
// being cast (a float-to-integer cast out of range is undefined behaviour).
std::uint64_t uint_field(const nlohmann::json& j, const char* key, std::uint64_t hi, const std::string& where) {
    if (!j.contains(key)) return 0;
    const nlohmann::json& v = j.at(key);
    if (!v.is_number_unsigned() && !(v.is_number_integer() && v.get<long long>() >= 0))
        throw Error(where + key + " " + shown(v) + " must be a whole number in [0, " + std::to_string(hi) + "]");
    const std::uint64_t u = v.get<std::uint64_t>();
    if (u > hi) throw Error(where + key + " " + shown(v) + " must be a whole number in [0, " + std::to_string(hi) + "]");
    return u;
}

// A real field within the interval from lo to hi; `open` ends are excluded.
enum class Ends { closed, open_low, open_both };
double real_field(const nlohmann::json& j, const char* key, double lo, double hi, Ends ends, const std::string& where) {
    const nlohmann::json& v = j.at(key);
    const double d = v.is_number() ? v.get<double>() : NAN;
    const bool low_ok = ends == Ends::closed ? d >= lo : d > lo, high_ok = ends == Ends::open_both ? d < hi : d <= hi;
    if (!low_ok || !high_ok) {
        char range[96];
        std::snprintf(range, sizeof range, " must be a number in %s%g, %g%s", ends == Ends::closed ? "[" : "(", lo, hi,
                      ends == Ends::open_both ? ")" : "]");
        throw Error(where + key + " " + shown(v) + range);
    }
    return d;
}

}  // namespace

// Every number is checked against what a flight can have, so a typo (fps 0, hfov 600, a camera of
// 64000 pixels) is reported here with the file's name instead of as nonsense much later.
FlightInfo read_flight_info(const std::string& path) {
    const std::string text = io::read_input_file(path, io::kMaxJsonFileBytes, "flight.json");
    io::check_json_depth(text, path);  // a 100000-deep [[...]] would overflow the stack in dump()
    FlightInfo info;
    const std::string where = path + ": ";
    try {
        const nlohmann::json j = nlohmann::json::parse(text);
        info.scenario = j.value("scenario", "");
        info.map_file = j.value("map_file", "");
        // Left out (0): the map's resolution comes with the map (a GeoTIFF's, or localize's --mpp);
        // import-photos writes such folders.
        info.metres_per_pixel = j.contains("metres_per_pixel") ? real_field(j, "metres_per_pixel", 0, 1000, Ends::open_low, where) : 0;
        if (j.contains("origin"))
            info.origin = GeoOrigin{real_field(j["origin"], "latitude_deg", -90, 90, Ends::closed, where + "origin."),
                                    real_field(j["origin"], "longitude_deg", -180, 180, Ends::closed, where + "origin.")};
        if (info.origin) check_geo_origin(*info.origin, where + "origin");
        const auto& c = j.at("camera");
        info.camera = {int_field(c, "width", 2, 16384, where + "camera."), int_field(c, "height", 2, 16384, where + "camera."),
                       real_field(c, "hfov_deg", 1, 170, Ends::open_both, where + "camera.")};
        info.fps = j.contains("fps") ? real_field(j, "fps", 0, 1000, Ends::open_low, where) : 50.0;
        for (auto [key, year] : {std::pair{"map_year", &info.map_year}, std::pair{"rendered_year", &info.rendered_year}})
            if (j.contains(key) && (*year = int_field(j, key, 0, 3000, where)) != 0 && *year < 1900)
                throw Error(where + key + " " + std::to_string(*year) + " must be 0 (unknown) or a year from 1900");
        info.seed = uint_field(j, "seed", std::numeric_limits<std::uint64_t>::max(), where);
        info.frames = static_cast<std::size_t>(uint_field(j, "frames", 100'000'000, where));
        if (j.contains("latlon_source")) {
            const nlohmann::json& v = j.at("latlon_source");
            if (!v.is_string() || (v.get<std::string>() != "truth" && v.get<std::string>() != kLatLonCameraGps))
                throw Error(where + "latlon_source " + shown(v) + " must be \"truth\" or \"" + kLatLonCameraGps + "\"");
            info.latlon_source = v.get<std::string>();
        }
    } catch (const nlohmann::json::exception& e) {
        throw Error(path + ": not a valid flight description (" + io::quote_input(e.what(), 200) + ")");
    }
    info.camera.validate();
    return info;
}

// ---- writer ----

AirWriter::AirWriter(const std::string& folder, std::vector<std::string> extra_columns)
    : folder_(folder), extra_columns_(std::move(extra_columns)) {
    std::error_code ec;
    std::filesystem::create_directories(folder, ec);
    if (ec) throw Error(folder + ": cannot create folder (" + ec.message() + ")");
    for (const std::string& c : extra_columns_)
        if (std::find(kColumns.begin(), kColumns.end(), c) != kColumns.end() || c.empty())
            throw Error(folder + "/metadata.csv: extra column '" + c + "' is empty or one of the AIR columns");
    // Appended piece by piece: `"," + std::string` trips GCC 12's -Wrestrict false positive on aarch64 (GCC PR 105651).
    for (std::size_t i = 0; i < kColumns.size(); ++i) csv_.append(i ? "," : "").append(kColumns[i]);
    for (const std::string& c : extra_columns_) csv_.append(",").append(quote_if_needed(c));
    csv_ += "\n";
}

void AirWriter::write(const AirRecord& r, GrayView image, const std::vector<std::string>& extra) {
    if (closed_) throw Error(folder_ + "/metadata.csv: written after close()");
    if (r.filename.empty()) throw Error(folder_ + "/metadata.csv: a record has no file name");
    if (extra.size() != extra_columns_.size())
        throw Error(folder_ + "/metadata.csv: a record has " + std::to_string(extra.size()) + " extra fields for " +
                    std::to_string(extra_columns_.size()) + " extra columns");
    AirRecord copy = r;
    const auto check_group = [&](std::size_t first, std::size_t last) {  // NaN is an empty cell: the whole group or none
        std::size_t nans = 0;
        for (std::size_t c = first; c <= last; ++c) nans += std::isnan(*numeric_field(copy, c));
        if (nans && nans != last - first + 1)
            throw Error(folder_ + "/metadata.csv: " + r.filename + ": " + kColumns[first] + ".." + kColumns[last] +
                        " are partly NaN; a group of columns is given whole or left empty");
    };
    for (const ColumnGroup& g : kOptionalGroups) check_group(g.first, g.last);
    if (!image.empty()) save_gray(folder_ + "/" + r.filename, image);
    static const char* const kFormats[] = {nullptr, "%.10f", "%.10f", "%.4f", "%.9f", "%.9f", "%.9f", "%.9f", "%.4f", "%.4f",
                                           "%.4f",  "%.9f",  "%.9f",  "%.9f", "%.9f", "%.3f", "%.3f", "%.4f", "%.4f", "%.4f"};
    csv_ += quote_if_needed(r.filename);
    char buf[64];
    for (std::size_t c = 1; c < kColumns.size(); ++c) {
        const double v = *numeric_field(copy, c);
        csv_ += ',';
        if (std::isnan(v)) continue;  // an empty cell: not measured (air_format.hpp)
        std::snprintf(buf, sizeof buf, kFormats[c], v);
        csv_ += buf;
    }
    for (const std::string& e : extra)  // outside text (a photo's name, EXIF); not "," + string: GCC PR 105651
        csv_.append(",").append(quote_if_needed(io::utf8_replaced(e)));
    csv_ += "\n";
}

void AirWriter::close() {
    if (closed_) return;
    io::write_file_atomic(folder_ + "/metadata.csv", csv_);
    closed_ = true;
}

// ---- parser ----

AirMetadataParser::AirMetadataParser(std::istream& in, std::string source) : in_(in), source_(std::move(source)) {
    std::string header;
    while (std::getline(in_, header)) {
        ++line_;
        if (!trim(header).empty()) break;
    }
    if (trim(header).empty()) throw Error(source_ + ": empty file, expected a header line with " + kColumns[0] + ",...");
    if (header.rfind("\xEF\xBB\xBF", 0) == 0) header.erase(0, 3);  // UTF-8 byte order mark
    if (header.size() > kMaxLineBytes)
        throw Error(source_ + ":" + std::to_string(line_) + ": header of " + std::to_string(header.size()) + " bytes (at most " +
                    std::to_string(kMaxLineBytes) + "); not a metadata.csv");
    std::vector<std::string> names;
    std::string why;
    if (!split_csv(header, names, why)) throw Error(source_ + ":" + std::to_string(line_) + ": header: " + why);
    field_count_ = names.size();
    column_of_.assign(kColumns.size(), -1);
    for (std::size_t i = 0; i < names.size(); ++i)
        if (names[i] == kTimeColumn) {
            if (time_column_ >= 0) throw Error(source_ + ":" + std::to_string(line_) + ": column " + kTimeColumn + " appears twice");
            time_column_ = static_cast<int>(i);
        }
    for (std::size_t i = 0; i < names.size(); ++i)
        for (std::size_t c = 0; c < kColumns.size(); ++c)
            if (names[i] == kColumns[c]) {
                if (column_of_[c] >= 0)
                    throw Error(source_ + ":" + std::to_string(line_) + ": column " + kColumns[c] + " appears twice");
                column_of_[c] = static_cast<int>(i);
            }
    for (std::size_t c = 0; c < kColumns.size(); ++c)
        if (column_of_[c] < 0) throw Error(source_ + ":" + std::to_string(line_) + ": header lacks the column " + kColumns[c]);
}

bool AirMetadataParser::next(AirRecord& r) {
    std::string text;
    std::vector<std::string> fields;
    while (std::getline(in_, text)) {
        ++line_;
        if (trim(text).empty()) continue;
        const std::string at = source_ + ":" + std::to_string(line_) + ": ";
        if (text.size() > kMaxLineBytes)
            throw Error(at + "row of " + std::to_string(text.size()) + " bytes (at most " + std::to_string(kMaxLineBytes) + ")");
        std::string why;
        if (!split_csv(text, fields, why)) throw Error(at + why);
        if (fields.size() != field_count_)
            throw Error(at + "expected " + std::to_string(field_count_) + " fields like the header, got " +
                        std::to_string(fields.size()));
        r = AirRecord{};
        r.filename = fields[column_of_[0]];
        if (r.filename.empty()) throw Error(at + "Filename is empty");
        // Groups of columns a flight may not have (air_format.hpp): all cells of a group empty is
        // NaN; one empty cell in a group otherwise given is a broken row.
        for (std::size_t c = 1; c < kColumns.size(); ++c) {
            const std::string& f = fields[column_of_[c]];
            const ColumnGroup* g = group_of(c);
            if (g && group_empty(*g, fields, column_of_)) {
                *numeric_field(r, c) = NAN;
                continue;
            }
            double v = 0;
            const auto [ptr, ec] = std::from_chars(f.data(), f.data() + f.size(), v);
            if (f.empty() || ec != std::errc() || ptr != f.data() + f.size())
                throw Error(at + kColumns[c] + " '" + io::quote_input(f, 40) + "' is not a number" +
                            (f.empty() && g ? " (" + std::string(g->name) + " are given all or left all empty)" : ""));
            if (!std::isfinite(v)) throw Error(at + kColumns[c] + " is not finite");
            if (const std::string why = implausible(c, v); !why.empty()) throw Error(at + why);
            *numeric_field(r, c) = v;
        }
        for (const auto& [q, prefix] : {std::pair{&r.imu, "Imu"}, std::pair{&r.orientation, "Orientation"}})
            if (!std::isnan(q->w))  // NaN: the group is empty (not measured)
                if (const std::string why = not_unit(*q, prefix); !why.empty()) throw Error(at + why);
        if (time_column_ >= 0) r.time_s = parse_time(fields[time_column_], at);
        check_order(r.filename, at);
        return true;
    }
    if (in_.bad()) throw Error(source_ + ": read error");
    return false;
}

// TimeS: empty is unknown; otherwise a finite number of seconds, never below the previous row's.
double AirMetadataParser::parse_time(const std::string& f, const std::string& at) {
    if (trim(f).empty()) return NAN;
    double v = 0;
    const auto [ptr, ec] = std::from_chars(f.data(), f.data() + f.size(), v);
    if (ec != std::errc() || ptr != f.data() + f.size() || !std::isfinite(v) || std::abs(v) > kMaxTimeS)
        throw Error(at + kTimeColumn + " '" + io::quote_input(f, 40) + "' is not a time in seconds (a finite number within +-" +
                    std::to_string(static_cast<long long>(kMaxTimeS)) + ", or empty: unknown)");
    if (v < last_time_s_)
        throw Error(at + kTimeColumn + " " + f + " is before the previous row's " + std::to_string(last_time_s_) +
                    " s; rows must be in time order");
    last_time_s_ = v;
    return v;
}

// Rows are frames in time order: a file name listed twice, or a frame number that does not grow
// (frame_000005.png after frame_000007.png), means rows were duplicated or shuffled, which would
// silently play the flight in the wrong order.
void AirMetadataParser::check_order(const std::string& filename, const std::string& at) {
    const auto [it, added] = first_line_of_.emplace(filename, line_);
    if (!added) throw Error(at + io::quote_input(filename) + " is listed again (first on line " + std::to_string(it->second) + "); rows are duplicated");
    const std::string number = trailing_number(filename);
    if (!number.empty() && !last_number_.empty() && number_less_or_equal(number, last_number_))
        throw Error(at + io::quote_input(filename) + " comes after " + io::quote_input(last_filename_) + "; rows must be in frame (time) order");
    if (!number.empty()) last_number_ = number, last_filename_ = filename;
}

// ---- reader ----

AirReader::AirReader(const std::string& folder) : folder_(folder) {
    const std::string path = folder + "/metadata.csv";
    // Read whole after the file checks: a FIFO or /dev/zero as metadata.csv is refused at once.
    try {
        text_ = io::read_input_file(path, io::kMaxTableFileBytes, "metadata.csv", &identity_);
    } catch (const Error& e) {
        const std::string why = e.what();
        throw Error(why.find(": no such file") != std::string::npos ? path + ": no such file (is " + folder + " an AIR flight folder?)" : why);
    }
    buffer_ = std::make_unique<ViewBuffer>(text_);
    stream_ = std::make_unique<std::istream>(buffer_.get());
    parser_ = std::make_unique<AirMetadataParser>(*stream_, path);
}

bool AirReader::unchanged() const { return io::file_identity(folder_ + "/metadata.csv") == identity_; }

bool AirReader::next(AirRecord& r) {
    if (parser_->next(r)) return ++rows_, true;
    if (rows_ == 0) throw Error(folder_ + "/metadata.csv: no frame rows after the header; the flight is empty");
    return false;
}

std::string AirReader::image_path(const AirRecord& r) const { return folder_ + "/" + r.filename; }

GrayImage AirReader::load_image(const AirRecord& r) const { return load_gray(image_path(r)); }

}  // namespace trn::sim
