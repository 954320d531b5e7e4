#pragma once
// Numeric options of every trnkit subcommand, checked when the command line is parsed: a count
// is plain decimal digits within stated bounds (so "-1" never wraps to 2^64-1 and 1e20 never
// saturates), a real is finite and within a stated interval (so nan/inf never slip through as
// "use the default"). A bad value stops the command with a message naming the option.
#include <cstdint>
#include <limits>
#include <string>

#include <CLI/CLI.hpp>

#include "trn/limits.hpp"

namespace trn::cli {

// CLI11 transform: a whole number in [lo, hi]; rewrites the text to canonical decimal so CLI11's
// own conversion (strtoull with base 0) reads the value that was checked. Help shows "in [lo, hi]".
CLI::Validator whole_in(std::uint64_t lo, std::uint64_t hi);

// --template-width: "full" (frames scored at full resolution; rewritten to 0, BackendScorerOptions'
// "keep") or a whole number of pixels in [8, kMaxTemplateWidth].
CLI::Validator template_width_option();

// Any unsigned 64-bit seed ("in [0, 2^64-1]", no sign).
CLI::Validator any_seed();

// Bounds shared by several subcommands (stated in their help through the validators).
inline constexpr std::uint64_t kMaxParticles = trn::limits::kMaxParticles;  // particles scored per frame (trn/limits.hpp)
inline constexpr std::uint64_t kMinYear = 1900, kMaxYear = 2200;  // map / flight years
inline constexpr std::uint64_t kMaxTemplateWidth = 4096;    // downscaled template width, pixels

// Which ends of a real interval are excluded.
enum class Open { none, low, high, both };

// CLI11 check: a finite real in the interval [lo, hi] (ends excluded as `open` says).
CLI::Validator real_in(double lo, double hi, Open open = Open::none);

}  // namespace trn::cli
