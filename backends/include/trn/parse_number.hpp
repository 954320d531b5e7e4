#pragma once
// Strict, overflow-safe parsing of numbers typed by a person (options, device specs, shards):
// the whole text must be the number, in plain decimal. Unlike strtoul/stoi/sscanf these never
// wrap "-1" to 2^64-1, never saturate on overflow, never read "010" as octal and never throw.
#include <charconv>
#include <cmath>
#include <cstdint>
#include <optional>
#include <string_view>
#include "trn/export.hpp"

TRN_API_BEGIN
namespace trn {

// A whole number written with decimal digits only (no sign, no spaces); nullopt otherwise or
// when it does not fit in 64 bits.
inline std::optional<std::uint64_t> parse_whole_number(std::string_view text) {
    if (text.empty() || text.front() < '0' || text.front() > '9') return std::nullopt;
    std::uint64_t v = 0;
    const auto [ptr, ec] = std::from_chars(text.data(), text.data() + text.size(), v, 10);
    if (ec != std::errc() || ptr != text.data() + text.size()) return std::nullopt;
    return v;
}

// A finite decimal real ("-1.5", "2e3"); nullopt for anything else, including nan and inf.
inline std::optional<double> parse_finite_real(std::string_view text) {
    double v = 0;
    const auto [ptr, ec] = std::from_chars(text.data(), text.data() + text.size(), v);
    if (text.empty() || ec != std::errc() || ptr != text.data() + text.size() || !std::isfinite(v)) return std::nullopt;
    return v;
}

}  // namespace trn
TRN_API_END
