// Fixed UTC offsets and tz database zones (TZif files, RFC 8536) for logs stamped in local time.
#include "trn/energy/time_zone.hpp"

#include <algorithm>
#include <cctype>
#include <optional>
#include <cmath>
#include <cstdint>
#include <cstdio>

#include "text_input.hpp"
#include "trn/error.hpp"

namespace trn::energy {
namespace {

std::int64_t be(const std::string& d, std::size_t at, int bytes, const std::string& path) {
    if (at + static_cast<std::size_t>(bytes) > d.size()) throw Error(path + ": truncated TZif file");
    std::uint64_t v = 0;
    for (int i = 0; i < bytes; ++i) v = (v << 8) | static_cast<unsigned char>(d[at + i]);
    if (bytes == 4) return static_cast<std::int32_t>(static_cast<std::uint32_t>(v));
    return static_cast<std::int64_t>(v);
}

// A tz name is letters, digits and _+- separated by single '/': never absolute, never "..".
bool plain_zone_name(const std::string& n) {
    if (n.empty() || n.size() > 64 || n.front() == '/' || n.back() == '/') return false;
    for (char c : n)
        if (!(std::isalnum(static_cast<unsigned char>(c)) || c == '_' || c == '+' || c == '-' || c == '/')) return false;
    for (auto part : text::split(n, '/'))
        if (part.empty() || part.front() == '-') return false;
    return true;
}

}  // namespace

TimeZone TimeZone::fixed(std::string_view text_in, const std::string& option) {
    const std::string_view s = text::trim(text_in);
    TimeZone z;
    z.name_ = "UTC" + std::string(s);
    z.offsets_ = {0};
    if (s == "UTC" || s == "Z" || s == "0") return z;
    auto bad = [&] { return Error(option + " '" + std::string(text_in) + "': expected +HH:MM, -HHMM or +H (UTC offset of the log's clock)"); };
    if (s.size() < 2 || (s[0] != '+' && s[0] != '-')) throw bad();
    std::string digits;
    for (char c : s.substr(1))
        if (c != ':') digits += c;
    if (digits.empty()) throw bad();
    for (char c : digits)
        if (!std::isdigit(static_cast<unsigned char>(c))) throw bad();
    int h = 0, m = 0;
    if (digits.size() <= 2) h = std::stoi(digits);
    else if (digits.size() == 4) h = std::stoi(digits.substr(0, 2)), m = std::stoi(digits.substr(2));
    else throw bad();
    if (h > 14 || m > 59) throw bad();
    z.offsets_ = {(s[0] == '-' ? -1 : 1) * (h * 3600.0 + m * 60.0)};
    return z;
}

TimeZone TimeZone::named(const std::string& name, const std::string& dir) {
    if (!plain_zone_name(name)) throw Error("timezone '" + name + "': not a tz database name such as Europe/Vilnius or America/New_York");
    const std::string path = dir + "/" + name;
    std::string d;
    try {
        d = text::read_file(path, 1 << 20);
    } catch (const Error&) {
        throw Error("timezone '" + name + "': no such zone (" + path + " cannot be read; is tzdata installed?)");
    }
    if (d.size() < 44 || d.compare(0, 4, "TZif") != 0) throw Error(path + ": not a TZif file");
    // Version 2+ files repeat the data with 64-bit times after the 32-bit block: use those.
    std::size_t at = 0;
    int time_bytes = 4;
    auto counts = [&](std::size_t h, std::int64_t c[6]) {
        for (int i = 0; i < 6; ++i) c[i] = be(d, h + 20 + 4 * i, 4, path);
    };
    std::int64_t c[6];
    counts(0, c);
    if (d[4] >= '2') {
        const std::int64_t v1 = c[3] * 4 + c[3] + c[4] * 6 + c[5] + c[2] * 8 + c[1] + c[0];
        at = 44 + static_cast<std::size_t>(v1);
        if (d.compare(at, 4, "TZif") != 0) throw Error(path + ": bad version-2 header");
        counts(at, c);
        time_bytes = 8;
    }
    const std::int64_t timecnt = c[3], typecnt = c[4];
    if (typecnt < 1 || typecnt > 256 || timecnt < 0 || timecnt > 100000) throw Error(path + ": implausible TZif counts");
    std::size_t p = at + 44;
    const std::size_t idx = p + static_cast<std::size_t>(timecnt) * time_bytes, types = idx + static_cast<std::size_t>(timecnt);
    std::vector<double> type_off(static_cast<std::size_t>(typecnt));
    for (std::int64_t i = 0; i < typecnt; ++i) type_off[i] = static_cast<double>(be(d, types + 6 * i, 4, path));
    TimeZone z;
    z.name_ = name;
    // Before the first transition: the first standard-time type (RFC 8536 3.2), in practice type 0.
    z.offsets_.push_back(type_off[0]);
    for (std::int64_t i = 0; i < timecnt; ++i) {
        z.transitions_.push_back(static_cast<double>(be(d, p + i * time_bytes, time_bytes, path)));
        const auto k = static_cast<unsigned char>(d.at(idx + i));
        if (k >= type_off.size()) throw Error(path + ": bad type index");
        z.offsets_.push_back(type_off[k]);
    }
    // The footer's POSIX rule covers times after the table; a rule with DST changes (a ',') is not
    // evaluated here, so such times are refused rather than guessed.
    const std::size_t footer = d.rfind('\n', d.size() - 2);
    if (time_bytes == 8 && footer != std::string::npos && d.find(',', footer) != std::string::npos && !z.transitions_.empty())
        z.last_valid_utc_ = z.transitions_.back();
    return z;
}

double TimeZone::offset_at_utc(double t) const {
    if (t > last_valid_utc_)
        throw Error("timezone " + name_ + ": the zone table ends before this log's time stamps; give the offset as utc_offset instead");
    const auto k = std::upper_bound(transitions_.begin(), transitions_.end(), t) - transitions_.begin();
    return offsets_[static_cast<std::size_t>(k)];
}

double TimeZone::local_to_utc(double local, bool* ambiguous) const {
    // Each offset in force near `local` gives a candidate; a candidate is valid when the zone
    // really has that offset at that UTC time. Two valid ones: the repeated hour (take the earlier).
    std::vector<double> valid;
    const double guess = offset_at_utc(local);
    for (double off : {offset_at_utc(local - guess - 86400), guess, offset_at_utc(local - guess + 86400)}) {
        const double u = local - off;
        if (offset_at_utc(u) == off && std::find(valid.begin(), valid.end(), u) == valid.end()) valid.push_back(u);
    }
    if (ambiguous) *ambiguous = valid.size() > 1;
    // No valid candidate: a time skipped when clocks go forward; read it with the offset before the gap.
    return valid.empty() ? local - offset_at_utc(local - guess - 86400) : *std::min_element(valid.begin(), valid.end());
}

std::optional<TimeZone> take_time_zone(ParseOptions& o) {
    const auto tz = o.find("timezone"), off = o.find("utc_offset");
    if (tz != o.end() && off != o.end()) throw Error("timezone and utc_offset: give one of them");
    std::optional<TimeZone> z;
    if (tz != o.end()) z = TimeZone::named(tz->second), o.erase(tz);
    else if (off != o.end()) z = TimeZone::fixed(off->second), o.erase(off);
    return z;
}

void apply_time_zone(PowerTrace& tr, const TimeZone& zone) {
    if (!tr.local_time)
        throw Error(tr.source + ": timezone/utc_offset given, but this " + tr.format + " log has no local wall-clock time stamps " +
                    (tr.wall_clock ? "(its stamps carry their zone or are UNIX time)" : "(its times are relative)"));
    std::size_t ambiguous = 0;
    auto conv = [&](double& t) {
        bool amb = false;
        t = zone.local_to_utc(t, &amb);
        ambiguous += amb;
    };
    for (double& t : tr.t) conv(t);
    for (auto& m : tr.markers) conv(m.t);
    if (tr.first_interval_start) conv(*tr.first_interval_start);
    for (std::size_t i = 1; i < tr.t.size(); ++i)
        if (!(tr.t[i] > tr.t[i - 1])) throw Error(tr.source + ": times are not increasing after converting " + zone.name() + " local time to UTC");
    tr.local_time = false;
    char buf[160];
    std::snprintf(buf, sizeof buf, "local time stamps converted to UTC with zone %s (offset %+g h at the first sample)", zone.name().c_str(),
                  zone.offset_at_utc(tr.t.front()) / 3600);
    bool replaced = false;
    for (auto& n : tr.notes)
        if (n.find("taken as UTC") != std::string::npos) n = buf, replaced = true;
    if (!replaced) tr.notes.push_back(buf);
    if (ambiguous) tr.notes.push_back(std::to_string(ambiguous) + " stamp(s) fall in the hour repeated when clocks go back: the earlier reading was taken");
}

}  // namespace trn::energy
