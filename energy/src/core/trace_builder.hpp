#pragma once
// Collects samples for a parser: refuses a time that goes backwards (names the line), drops
// readings beyond the source's plausibility cap into the trace's warnings, refuses a negative
// reading where the source cannot draw negative power and warns where it can, counts rows dropped
// for a reason and turns the counts into the trace's notes (a warning when most of a log went).
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>
#include <string>

#include "option_reader.hpp"
#include "text_input.hpp"
#include "trn/energy/trace.hpp"

namespace trn::energy {

// A power unit read from a header is evidence, not truth. When every reading, in that unit, is
// beyond what the source can draw (below its floor or above its cap) while another power unit
// would put them all in range, the log is refused naming both readings and the option that
// settles it ("Power (mW)" over Raspberry Pi 5 values 3.3-9.2: a computer drawing 4 mW). Only
// for units taken from a header; a unit given as an option is the user's word and is not tested.
inline void check_power_unit_against_source(const std::string& file, const std::string& column, double scale, const std::vector<double>& raw,
                                            const PowerSource& src, const std::string& option) {
    if (raw.empty()) return;
    double lo = std::abs(raw.front()), hi = lo;
    for (double v : raw) lo = std::min(lo, std::abs(v)), hi = std::max(hi, std::abs(v));
    static const std::pair<const char*, double> units[] = {{"uW", 1e-6}, {"mW", 1e-3}, {"W", 1}, {"kW", 1e3}};
    auto fits = [&](double s) { return hi * s >= src.min_w && lo * s <= src.max_w && hi * s <= src.max_w; };
    if (fits(scale) || !(hi * scale < src.min_w || lo * scale > src.max_w)) return;
    const char* said = "?";
    for (const auto& [u, s] : units)
        if (s == scale) said = u;
    // the fitting unit nearest the header's (a slip of one prefix is the usual error)
    const std::pair<const char*, double>* best = nullptr;
    for (const auto& c : units)
        if (c.second != scale && fits(c.second) && (!best || std::abs(std::log10(c.second / scale)) < std::abs(std::log10(best->second / scale))))
            best = &c;
    char buf[700];
    if (best) {
        const auto& [u, s] = *best;
        std::snprintf(buf, sizeof buf,
                      "%s: power column '%s' says %s, but in %s its readings (%g to %g) are %g to %g W, %s than %s %s (%s %g W); in %s they "
                      "would be %g to %g W. Pass %s=%s if they are %s, or %s=%s to keep the header's unit (source= names another kind of device)",
                      file.c_str(), column.c_str(), said, said, lo, hi, lo * scale, hi * scale, hi * scale < src.min_w ? "less" : "more",
                      src.description.c_str(), hi * scale < src.min_w ? "draws" : "can draw", hi * scale < src.min_w ? "at least" : "at most",
                      hi * scale < src.min_w ? src.min_w : src.max_w, u, lo * s, hi * s, option.c_str(), u, u, option.c_str(), said);
        throw Error(buf);
    }
}

// The same test for an energy counter whose unit came from its header ("energy_uj" counting
// mJ): `w` are the interval-mean powers its rises give in that unit. When all of them lie below
// the source's floor or above its cap while another energy unit would put them in range, the log
// is refused naming both readings and energy_unit=.
inline void check_energy_unit_against_source(const std::string& file, const std::string& column, double scale, const std::vector<double>& w,
                                             const PowerSource& src) {
    if (w.empty()) return;
    double lo = std::abs(w.front()), hi = lo;
    for (double v : w) lo = std::min(lo, std::abs(v)), hi = std::max(hi, std::abs(v));
    static const std::pair<const char*, double> units[] = {{"uJ", 1e-6}, {"mJ", 1e-3}, {"J", 1}, {"mWh", 3.6}, {"Wh", 3600}, {"kWh", 3.6e6}};
    auto fits = [&](double s) { return hi * s / scale >= src.min_w && hi * s / scale <= src.max_w; };
    if (!(hi < src.min_w || lo > src.max_w)) return;  // some interval within what the source draws
    const char* said = "?";
    for (const auto& [u, s] : units)
        if (s == scale) said = u;
    const std::pair<const char*, double>* best = nullptr;
    for (const auto& c : units)
        if (c.second != scale && fits(c.second) && (!best || std::abs(std::log10(c.second / scale)) < std::abs(std::log10(best->second / scale))))
            best = &c;
    if (!best) return;
    char buf[700];
    std::snprintf(buf, sizeof buf,
                  "%s: energy counter '%s' says %s, but counted in %s its rises are %g to %g W, %s than %s %s (%s %g W); in %s they would be "
                  "%g to %g W. Pass energy_unit=%s if it counts %s, or energy_unit=%s to keep the header's unit (source= names another kind of device)",
                  file.c_str(), column.c_str(), said, said, lo, hi, hi < src.min_w ? "less" : "more", src.description.c_str(),
                  hi < src.min_w ? "draws" : "can draw", hi < src.min_w ? "at least" : "at most", hi < src.min_w ? src.min_w : src.max_w, best->first,
                  lo * best->second / scale, hi * best->second / scale, best->first, best->first, said);
    throw Error(buf);
}

class TraceBuilder {
public:
    TraceBuilder(std::string source, std::string format) {
        trace_.source = std::move(source);
        trace_.format = std::move(format);
    }
    PowerTrace& trace() { return trace_; }

    // The source whose cap and sign rules apply (power_sources()), and max_power_w= when given.
    // `times` scales the cap (gpu=all: N boards).
    void power_source(const std::string& name, const OptionReader& o, double times = 1) {
        source_ = trn::energy::power_source(name);
        source_.max_w *= times;
        if (times > 1) source_.description = std::to_string(static_cast<int>(times)) + " x " + source_.description;
        if (const auto cap = o.number("max_power_w")) {
            if (!(*cap > 0)) throw Error(trace_.source + ": option max_power_w must be > 0");
            source_.max_w = *cap;
            cap_given_ = true;
        }
    }
    const PowerSource& power_source() const { return source_; }

    // Adds a sample; a time equal to the previous one is dropped as a duplicate stamp, an
    // earlier one is an error (the log is out of order or the clock stepped back).
    void add(std::size_t line, double t, double w) {
        ++rows_;
        if (!trace_.t.empty() && t <= trace_.t.back()) {
            if (t == trace_.t.back()) {
                ++same_stamp_;
                drop(line, "same time stamp as the row before");
                return;
            }
            text::fail(trace_.source, line, "time goes backwards (" + std::to_string(t) + " s after " +
                                                std::to_string(trace_.t.back()) + " s)");
        }
        if (!(std::abs(w) <= source_.max_w)) {
            if (implausible_++ == 0) first_implausible_w_ = w;
            drop(line, kImplausible);
            return;
        }
        if (w < 0) {
            if (!source_.can_be_negative) {
                char buf[160];
                std::snprintf(buf, sizeof buf, "negative power %g W, which %s cannot draw (a sign or decode error in the log)", w,
                              source_.description.c_str());
                text::fail(trace_.source, line, buf);
            }
            if (negative_++ == 0) first_negative_line_ = line;
            min_w_ = std::min(min_w_, w);
        }
        trace_.t.push_back(t);
        trace_.w.push_back(w);
    }
    void drop(std::size_t line, const std::string& reason) {
        auto& [count, first] = dropped_[reason];
        if (count++ == 0) first = line;
    }
    void note(std::string text) { trace_.notes.push_back(std::move(text)); }

    PowerTrace finish() {
        std::string why_few = dropped_.empty() ? "" : "; dropped rows: see the notes";
        char buf[400];
        if (implausible_) {
            std::snprintf(buf, sizeof buf, "dropped %zu implausible power reading(s) beyond +-%g W (the cap for %s%s; first at line %zu: %g W); "
                          "the trace is interpolated across them",
                          implausible_, source_.max_w, source_.description.c_str(), cap_given_ ? ", max_power_w" : "; max_power_w= to change",
                          dropped_[kImplausible].second, first_implausible_w_);
            trace_.warnings.push_back(trace_.source + ": " + buf);
            why_few = std::string("; ") + buf;
        }
        if (negative_) {
            std::snprintf(buf, sizeof buf, "%zu negative power reading(s) kept as read (first at line %zu, lowest %g W): a reverse current or an "
                          "offset; they lower the joules", negative_, first_negative_line_, min_w_);
            trace_.warnings.push_back(trace_.source + ": " + buf);
        }
        for (const auto& [reason, cf] : dropped_)
            trace_.notes.push_back("dropped " + std::to_string(cf.first) + " row(s): " + reason + " (first at line " +
                                   std::to_string(cf.second) + ")");
        const std::string last_drop = dropped_.empty() ? "" : trace_.notes.back();
        if (same_stamp_ * 10 > rows_ && same_stamp_ > 0)
            trace_.warnings.push_back(trace_.source + ": dropped " + std::to_string(same_stamp_) + " of " + std::to_string(rows_) +
                                      " rows sharing the time stamp of the row before: the log is sampled faster than its stamps resolve");
        std::snprintf(buf, sizeof buf, "plausibility cap +-%g W (%s%s)", source_.max_w, source_.description.c_str(),
                      cap_given_ ? ", max_power_w" : "; max_power_w= to change");
        // once: a trnkit log written from a parsed trace carries it among its notes already
        if (std::find(trace_.notes.begin(), trace_.notes.end(), std::string(buf)) == trace_.notes.end()) trace_.notes.push_back(buf);
        recognise_unix_time();
        if (trace_.t.size() < 2)
            throw Error(trace_.source + ": fewer than two usable samples (" + std::to_string(trace_.t.size()) + ") in this " + trace_.format + " log" +
                        (implausible_ || dropped_.empty() ? why_few : "; " + last_drop));
        return std::move(trace_);
    }

private:
    // Numbers that can only be UNIX seconds (2000..2100; a relative clock or CLOCK_MONOTONIC
    // would mean decades of uptime) are absolute: the log then needs no alignment options.
    // trnkit's own format states its clock in the header and is left alone.
    void recognise_unix_time() {
        if (trace_.wall_clock || trace_.format == "trnkit" || trace_.t.empty()) return;
        if (trace_.t.front() >= kUnix2000 && trace_.t.back() <= kUnix2100) {
            trace_.wall_clock = true;
            trace_.notes.push_back("time values are UNIX epoch seconds (between 2000 and 2100): taken as absolute UTC time");
        }
    }
    static constexpr double kUnix2000 = 946684800, kUnix2100 = 4102444800;
    PowerTrace trace_;
    PowerSource source_ = trn::energy::power_source("node");
    bool cap_given_ = false;
    std::map<std::string, std::pair<std::size_t, std::size_t>> dropped_;
    static constexpr const char* kImplausible = "power beyond the source's plausibility cap (see warnings)";
    std::size_t implausible_ = 0, negative_ = 0, first_negative_line_ = 0, rows_ = 0, same_stamp_ = 0;
    double first_implausible_w_ = 0, min_w_ = 0;
};

}  // namespace trn::energy
