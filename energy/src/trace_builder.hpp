#pragma once
// Collects samples for a parser: refuses a time that goes backwards (names the line), drops
// physically implausible readings into the trace's warnings, counts rows dropped for a reason
// and turns the counts into the trace's notes.
#include <cstdio>
#include <map>
#include <string>

#include "text_input.hpp"
#include "trn/energy/trace.hpp"

namespace trn::energy {

class TraceBuilder {
public:
    TraceBuilder(std::string source, std::string format) {
        trace_.source = std::move(source);
        trace_.format = std::move(format);
    }
    PowerTrace& trace() { return trace_; }

    // Adds a sample; a time equal to the previous one is dropped as a duplicate stamp, an
    // earlier one is an error (the log is out of order or the clock stepped back).
    void add(std::size_t line, double t, double w) {
        if (!trace_.t.empty() && t <= trace_.t.back()) {
            if (t == trace_.t.back()) {
                drop(line, "same time stamp as the row before");
                return;
            }
            text::fail(trace_.source, line, "time goes backwards (" + std::to_string(t) + " s after " +
                                                std::to_string(trace_.t.back()) + " s)");
        }
        if (!(w >= kMinPlausibleW && w <= kMaxPlausibleW)) {
            if (implausible_++ == 0) first_implausible_w_ = w;
            drop(line, kImplausible);
            return;
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
        if (implausible_) {
            char buf[256];
            std::snprintf(buf, sizeof buf, "dropped %zu implausible power reading(s) outside [%g W, %g W] (first at line %zu: %g W); the trace is interpolated across them",
                          implausible_, kMinPlausibleW, kMaxPlausibleW, dropped_[kImplausible].second, first_implausible_w_);
            trace_.warnings.push_back(trace_.source + ": " + buf);
            why_few = std::string("; ") + buf;
        }
        for (const auto& [reason, cf] : dropped_)
            trace_.notes.push_back("dropped " + std::to_string(cf.first) + " row(s): " + reason + " (first at line " +
                                   std::to_string(cf.second) + ")");
        recognise_unix_time();
        if (trace_.t.size() < 2)
            throw Error(trace_.source + ": fewer than two usable samples (" + std::to_string(trace_.t.size()) + ") in this " + trace_.format + " log" +
                        (implausible_ || dropped_.empty() ? why_few : "; " + trace_.notes.back()));
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
    std::map<std::string, std::pair<std::size_t, std::size_t>> dropped_;
    static constexpr const char* kImplausible = "power outside the plausible range (see warnings)";
    std::size_t implausible_ = 0;
    double first_implausible_w_ = 0;
};

}  // namespace trn::energy
