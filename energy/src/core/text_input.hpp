#pragma once
// Shared reading helpers for the log parsers: lines with numbers (CRLF tolerated), strict
// number parsing (no NaN/inf), date/time parsing, and errors that name file:line.
#include <cstddef>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "trn/error.hpp"

namespace trn::energy::text {

struct Line {
    std::size_t number = 0;  // 1-based
    std::string_view text;   // without the line ending
};

std::vector<Line> split_lines(std::string_view text);
std::string_view trim(std::string_view s);
std::vector<std::string_view> split(std::string_view s, char sep);
std::vector<std::string_view> split_ws(std::string_view s);
std::string lower(std::string_view s);
// The separator of a CSV line: the one of ',', ';' and tab it holds most often (ties in that
// order), else 0: runs of whitespace (an aligned table).
char detect_delimiter(std::string_view line);
// Fields of one CSV row split at `delim` (0: runs of whitespace), each trimmed; a double-quoted
// field keeps its separators ("30,3", "Intel, Inc."), "" inside it is a quote.
std::vector<std::string> split_fields(std::string_view line, char delim);
bool starts_with(std::string_view s, std::string_view prefix);

// A finite number, or nullopt; the whole (trimmed) field must be consumed.
std::optional<double> to_number(std::string_view field);
// Seconds since 1970-01-01 for a proleptic-Gregorian civil date (UTC).
double civil_to_unix(int year, int month, int day, int hour, int minute, double second);

// "2026-03-18T12:09:03+05:30", "2026-03-18 12:09:03.5Z", "2024/10/30 18:42:33.189",
// "2025-09-08T17:26:50,123456789+08:00" (date --iso-8601=ns: a comma before the fraction),
// "10-01-2025 20:05:55" (MM-DD-YYYY, tegrastats). Returns UNIX seconds; zone-less stamps are
// taken as UTC and *zone_known is set false.
std::optional<double> parse_datetime(std::string_view s, bool* zone_known = nullptr);

[[noreturn]] void fail(const std::string& source, std::size_t line, const std::string& why);

// Most fields one row of a text log may split into. A field costs 16 to 40 bytes once split, so a
// 240 MB header of 126 M columns would take 2 to 5 GB before any parser could say it is not a log;
// real logs have at most a few hundred columns (a jtop CSV of a 12-core Orin: about 40).
constexpr std::size_t kMaxFieldsPerRow = std::size_t{1} << 16;
// Refuses, before anything splits it, the first line of `input` that ',', ';', tab or runs of
// whitespace would cut into more than kMaxFieldsPerRow fields: "NAME:LINE: a row of N fields ...".
void check_row_widths(std::string_view input, const std::string& name);

// The whole file as text, refusing one larger than max_bytes and anything but a regular file: a
// device such as /dev/zero or a FIFO given as an input would otherwise be read (or waited on) for
// ever. Errors name the path (io::read_input_file).
constexpr std::size_t kMaxInputBytes = std::size_t{256} << 20;        // power logs (hours at 1 kHz)
constexpr std::size_t kMaxSmallInputBytes = std::size_t{64} << 20;    // marker files, run reports
std::string read_file(const std::string& path, std::size_t max_bytes = kMaxInputBytes);

}  // namespace trn::energy::text
