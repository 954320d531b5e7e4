#include "text_input.hpp"

#include <algorithm>
#include <cctype>
#include <charconv>
#include <cmath>
#include <cstdio>

#include "trn/io/input_file.hpp"

namespace trn::energy::text {

std::vector<Line> split_lines(std::string_view text) {
    std::vector<Line> lines;
    std::size_t pos = 0, number = 1;
    while (pos < text.size()) {
        std::size_t end = text.find('\n', pos);
        if (end == std::string_view::npos) end = text.size();
        std::string_view l = text.substr(pos, end - pos);
        if (!l.empty() && l.back() == '\r') l.remove_suffix(1);
        lines.push_back({number++, l});
        pos = end + 1;
    }
    return lines;
}

std::string_view trim(std::string_view s) {
    while (!s.empty() && std::isspace(static_cast<unsigned char>(s.front()))) s.remove_prefix(1);
    while (!s.empty() && std::isspace(static_cast<unsigned char>(s.back()))) s.remove_suffix(1);
    return s;
}

std::vector<std::string_view> split(std::string_view s, char sep) {
    std::vector<std::string_view> out;
    std::size_t pos = 0;
    while (true) {
        const std::size_t end = s.find(sep, pos);
        out.push_back(s.substr(pos, end == std::string_view::npos ? std::string_view::npos : end - pos));
        if (end == std::string_view::npos) break;
        pos = end + 1;
    }
    return out;
}

std::vector<std::string_view> split_ws(std::string_view s) {
    std::vector<std::string_view> out;
    std::size_t i = 0;
    while (i < s.size()) {
        while (i < s.size() && std::isspace(static_cast<unsigned char>(s[i]))) ++i;
        const std::size_t start = i;
        while (i < s.size() && !std::isspace(static_cast<unsigned char>(s[i]))) ++i;
        if (i > start) out.push_back(s.substr(start, i - start));
    }
    return out;
}

char detect_delimiter(std::string_view line) {
    char best = 0;
    std::size_t most = 0;
    for (char c : {',', ';', '\t'}) {
        const auto n = static_cast<std::size_t>(std::count(line.begin(), line.end(), c));
        if (n > most) most = n, best = c;
    }
    return best;
}

std::vector<std::string> split_fields(std::string_view line, char delim) {
    std::vector<std::string> out;
    if (delim == 0) {
        for (auto f : text::split_ws(line)) out.emplace_back(f);
        return out;
    }
    std::string cur;
    bool quoted = false;
    for (std::size_t i = 0; i < line.size(); ++i) {
        const char c = line[i];
        if (quoted) {
            if (c == '"' && i + 1 < line.size() && line[i + 1] == '"') cur += '"', ++i;
            else if (c == '"') quoted = false;
            else cur += c;
        } else if (c == '"' && text::trim(cur).empty()) {
            cur.clear(), quoted = true;
        } else if (c == delim) {
            out.push_back(std::string(text::trim(cur))), cur.clear();
        } else {
            cur += c;
        }
    }
    out.push_back(std::string(text::trim(cur)));
    return out;
}

std::string lower(std::string_view s) {
    std::string out(s);
    std::transform(out.begin(), out.end(), out.begin(), [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
    return out;
}

bool starts_with(std::string_view s, std::string_view prefix) { return s.substr(0, prefix.size()) == prefix; }

std::optional<double> to_number(std::string_view field) {
    field = trim(field);
    if (field.empty()) return std::nullopt;
    if (field.front() == '+') field.remove_prefix(1);
    double v = 0;
    const auto [ptr, ec] = std::from_chars(field.data(), field.data() + field.size(), v);
    if (ec != std::errc() || ptr != field.data() + field.size() || !std::isfinite(v)) return std::nullopt;
    return v;
}

double civil_to_unix(int y, int m, int d, int hour, int minute, double second) {
    // Howard Hinnant's days_from_civil.
    y -= m <= 2;
    const long era = (y >= 0 ? y : y - 399) / 400;
    const long yoe = y - era * 400;
    const long doy = (153 * (m + (m > 2 ? -3 : 9)) + 2) / 5 + d - 1;
    const long doe = yoe * 365 + yoe / 4 - yoe / 100 + doy;
    const long days = era * 146097 + doe - 719468;
    return static_cast<double>(days) * 86400.0 + hour * 3600.0 + minute * 60.0 + second;
}

namespace {

bool read_int(std::string_view& s, int digits, int& out) {
    if (s.size() < static_cast<std::size_t>(digits)) return false;
    int v = 0;
    for (int i = 0; i < digits; ++i) {
        if (!std::isdigit(static_cast<unsigned char>(s[i]))) return false;
        v = v * 10 + (s[i] - '0');
    }
    out = v;
    s.remove_prefix(digits);
    return true;
}

bool eat(std::string_view& s, std::string_view chars) {
    if (s.empty() || chars.find(s.front()) == std::string_view::npos) return false;
    s.remove_prefix(1);
    return true;
}

}  // namespace

std::optional<double> parse_datetime(std::string_view s, bool* zone_known) {
    s = trim(s);
    int y = 0, mo = 0, d = 0, h = 0, mi = 0, sec = 0;
    std::string_view r = s;
    if (r.size() >= 10 && (r[4] == '-' || r[4] == '/')) {
        if (!read_int(r, 4, y) || !eat(r, "-/") || !read_int(r, 2, mo) || !eat(r, "-/") || !read_int(r, 2, d)) return std::nullopt;
    } else if (r.size() >= 10 && r[2] == '-' && r[5] == '-') {  // tegrastats MM-DD-YYYY
        if (!read_int(r, 2, mo) || !eat(r, "-") || !read_int(r, 2, d) || !eat(r, "-") || !read_int(r, 4, y)) return std::nullopt;
    } else if (r.size() >= 10 && r[2] == '.' && r[5] == '.') {  // DD.MM.YYYY (German wall meters and loggers)
        if (!read_int(r, 2, d) || !eat(r, ".") || !read_int(r, 2, mo) || !eat(r, ".") || !read_int(r, 4, y)) return std::nullopt;
    } else {
        return std::nullopt;
    }
    if (!eat(r, "T ") || !read_int(r, 2, h) || !eat(r, ":") || !read_int(r, 2, mi) || !eat(r, ":") || !read_int(r, 2, sec))
        return std::nullopt;
    double frac = 0;
    if (!r.empty() && (r.front() == '.' || r.front() == ',')) {  // ',': ISO 8601's other decimal sign (date --iso-8601=ns)
        std::size_t n = 1;
        while (n < r.size() && std::isdigit(static_cast<unsigned char>(r[n]))) ++n;
        if (n == 1) return std::nullopt;
        frac = *to_number("0." + std::string(r.substr(1, n - 1)));
        r.remove_prefix(n);
    }
    if (mo < 1 || mo > 12 || d < 1 || d > 31 || h > 23 || mi > 59 || sec > 60) return std::nullopt;
    double offset = 0;
    bool known = false;
    if (!r.empty() && (r.front() == 'Z' || r.front() == 'z')) {
        known = true;
        r.remove_prefix(1);
    } else if (!r.empty() && (r.front() == '+' || r.front() == '-')) {
        const int sign = r.front() == '-' ? -1 : 1;
        r.remove_prefix(1);
        int oh = 0, om = 0;
        if (!read_int(r, 2, oh)) return std::nullopt;
        eat(r, ":");
        if (!read_int(r, 2, om) || oh > 23 || om > 59) return std::nullopt;
        offset = sign * (oh * 3600.0 + om * 60.0);
        known = true;
    }
    if (!trim(r).empty()) return std::nullopt;
    if (zone_known) *zone_known = known;
    return civil_to_unix(y, mo, d, h, mi, sec + frac) - offset;
}

void fail(const std::string& source, std::size_t line, const std::string& why) {
    throw Error(source + ":" + std::to_string(line) + ": " + why);
}

void check_row_widths(std::string_view input, const std::string& name) {
    std::size_t line = 1, commas = 0, semicolons = 0, tabs = 0, tokens = 0;
    bool after_space = true;
    for (std::size_t i = 0; i <= input.size(); ++i) {
        const char c = i < input.size() ? input[i] : '\n';
        if (c != '\n') {
            commas += c == ',', semicolons += c == ';', tabs += c == '\t';
            const bool space = std::isspace(static_cast<unsigned char>(c)) != 0;
            tokens += !space && after_space;
            after_space = space;
            continue;
        }
        const std::size_t widest = std::max({commas + 1, semicolons + 1, tabs + 1, tokens});
        if (widest > kMaxFieldsPerRow) {
            char gb[32];
            std::snprintf(gb, sizeof gb, "%.1f", static_cast<double>(widest) * 32 / 1e9);
            fail(name, line, "a row of " + std::to_string(widest) + " fields, more than the " + std::to_string(kMaxFieldsPerRow) +
                                 " a log row may have (splitting it would take about " + gb + " GB of memory); not a power log, or a broken one");
        }
        ++line, commas = semicolons = tabs = tokens = 0, after_space = true;
    }
}

// The one open point of every energy input (power logs, markers, run reports): a regular file of
// at most max_bytes (trn/io/input_file.hpp), so a FIFO or device is refused instead of read for ever.
std::string read_file(const std::string& path, std::size_t max_bytes) { return io::read_input_file(path, max_bytes); }

}  // namespace trn::energy::text
