#include "trn/io/pose_csv.hpp"

#include <charconv>
#include <cmath>
#include <cstdio>
#include <istream>
#include <streambuf>
#include <sstream>

#include "trn/error.hpp"
#include "trn/io/input_file.hpp"
#include "trn/limits.hpp"

namespace trn {
namespace {

std::string trim(std::string_view s) {
    const auto b = s.find_first_not_of(" \t\r");
    if (b == std::string_view::npos) return {};
    const auto e = s.find_last_not_of(" \t\r");
    return std::string(s.substr(b, e - b + 1));
}

// A stream over text already in memory (no copy, unlike std::istringstream).
struct ViewBuffer : std::streambuf {
    explicit ViewBuffer(std::string_view s) {
        char* p = const_cast<char*>(s.data());
        setg(p, p, p + s.size());
    }
};

// Plausible magnitudes: far beyond any map (sides <= 65536 px) or turn count, small enough that
// the affine arithmetic on them stays meaningful (a yaw of 3e38 rad has no direction left in a float).
constexpr float kMaxPosition = 1e7f;  // x, y: map pixels
constexpr float kMaxYaw = 1000.0f;    // radians (~160 turns; a float still resolves 6e-5 rad there)
constexpr float kMaxScale = 1e4f;     // map pixels per template pixel
constexpr std::size_t kMaxLineBytes = 4096;

}  // namespace

std::vector<Pose> read_poses_csv(std::istream& in, const std::string& source, std::int64_t max_poses) {
    std::vector<Pose> poses;
    std::string line;
    int line_no = 0;
    bool first_content = true;
    while (std::getline(in, line)) {
        ++line_no;
        if (line_no == 1) line = std::string(io::strip_bom(line));  // a UTF-8 byte order mark (spreadsheet export)
        if (line.size() > kMaxLineBytes)
            throw Error(source + ":" + std::to_string(line_no) + ": line of " + std::to_string(line.size()) + " bytes (at most " +
                        std::to_string(kMaxLineBytes) + "); not a pose file?");
        const std::string t = trim(line);
        if (t.empty() || t[0] == '#') continue;
        std::vector<std::string> fields;
        std::stringstream ss(t);
        for (std::string f; std::getline(ss, f, ',');) fields.push_back(trim(f));
        if (first_content) {
            first_content = false;
            if (!fields.empty() && fields[0] == "x") {  // header
                if (fields.size() != 4 || fields[1] != "y" || fields[2] != "yaw" || fields[3] != "scale")
                    throw Error(source + ":" + std::to_string(line_no) + ": header must be x,y,yaw,scale");
                continue;
            }
        }
        if (fields.size() != 4)
            throw Error(source + ":" + std::to_string(line_no) + ": expected 4 fields x,y,yaw,scale, got " +
                        std::to_string(fields.size()));
        float v[4];
        for (int k = 0; k < 4; ++k) {
            const std::string& f = fields[k];
            const auto [ptr, ec] = std::from_chars(f.data(), f.data() + f.size(), v[k]);
            if (ec != std::errc() || ptr != f.data() + f.size() || f.empty())
                throw Error(source + ":" + std::to_string(line_no) + ": field " + std::to_string(k + 1) + " '" + io::quote_input(f) +
                            "' is not a number");
            if (!std::isfinite(v[k]))
                throw Error(source + ":" + std::to_string(line_no) + ": field " + std::to_string(k + 1) + " is not finite");
        }
        if (!(v[3] > 0)) throw Error(source + ":" + std::to_string(line_no) + ": scale must be > 0");
        const float bound[4] = {kMaxPosition, kMaxPosition, kMaxYaw, kMaxScale};
        static const char* const names[4] = {"x", "y", "yaw", "scale"};
        for (int k = 0; k < 4; ++k)
            if (std::fabs(v[k]) > bound[k]) {
                char buf[96];
                std::snprintf(buf, sizeof buf, ": %s %g is beyond %g", names[k], double(v[k]), double(bound[k]));
                throw Error(source + ":" + std::to_string(line_no) + buf + (k == 2 ? " rad" : ""));
            }
        if (static_cast<std::int64_t>(poses.size()) >= max_poses)  // stop before the vector grows further
            limits::check_count(source + ":" + std::to_string(line_no) + ": pose count",
                                static_cast<std::int64_t>(poses.size()) + 1, max_poses, limits::kParticleBytes);
        poses.push_back({v[0], v[1], v[2], v[3]});
    }
    if (in.bad()) throw Error(source + ": read error");
    return poses;
}

// Read whole after the file checks (a FIFO or /dev/zero is refused, not read for ever), then parsed.
std::vector<Pose> read_poses_csv(const std::string& path) {
    const std::string text = io::read_input_file(path, io::kMaxTableFileBytes, "a pose file");
    ViewBuffer buffer(text);
    std::istream in(&buffer);
    return read_poses_csv(in, path);
}

}  // namespace trn
