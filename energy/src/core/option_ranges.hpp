#pragma once
// The stated range of every numeric parser option (`--opt KEY=VALUE`, issue 45 class 6 / 46):
// `period_s=1e308` or `1e-300` used to be taken (rows 1e308 s apart, or a trace of one instant).
// OptionReader::number checks each value here before a parser sees it and refuses one outside,
// naming the option, the value and the range; a numeric option without an entry is a defect
// (refused the same way; `energy.option_ranges_stated` fails on it). docs/ENERGY.md lists them.
#include <array>
#include <string_view>

namespace trn::energy {

struct OptionRange {
    std::string_view key;
    double min, max;        // inclusive
    bool whole;             // an integer
    std::string_view unit;  // as the message prints it after the range
};

inline constexpr std::array<OptionRange, 13> kOptionRanges{{
    {"period_s", 1e-6, 3600, false, "s (a sample every microsecond to one an hour)"},
    {"interval_s", 1e-6, 3600, false, "s"},
    {"interval_ms", 1e-3, 3.6e6, false, "ms (a microsecond to an hour)"},
    {"tick_period_s", 1e-9, 3600, false, "s"},
    {"tick_bits", 8, 32, true, "bits"},
    {"voltage", 1e-3, 1000, false, "V"},
    {"max_energy_range_uj", 1, 18446744073709551616.0, false, "uJ (at most 2^64, a 64-bit counter)"},
    {"max_bus_v", 1e-3, 1000, false, "V"},
    {"max_power_w", 1e-3, 1e9, false, "W"},
    {"shunt_ohm", 1e-6, 1e6, false, "ohm"},
    {"current_lsb", 1e-12, 1, false, "A per bit"},
    {"cal", 0, 65535, true, "(a 16-bit register)"},
    {"pga_mv", 40, 320, true, "mV"},
}};

inline const OptionRange* option_range(std::string_view key) {
    for (const OptionRange& r : kOptionRanges)
        if (r.key == key) return &r;
    return nullptr;
}

}  // namespace trn::energy
