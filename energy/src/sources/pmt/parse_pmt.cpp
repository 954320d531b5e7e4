// PMT (Power Measurement Toolkit) dump files, with their "M <t> \"label\"" markers.
#include <algorithm>
#include <cmath>
#include <cstdio>

#include "option_reader.hpp"
#include "trace_builder.hpp"
#include "trn/energy/parsers.hpp"

namespace trn::energy {

PowerTrace parse_pmt(std::string_view input, const std::string& name, const ParseOptions& options) {
    const std::string parser = name + " (pmt)";
    OptionReader o(options, parser, {"column", "max_power_w"});
    const auto lines = text::split_lines(input);
    std::size_t hi = 0;
    while (hi < lines.size() && text::trim(lines[hi].text).empty()) ++hi;
    if (hi == lines.size()) throw Error(parser + ": empty file");
    const auto header = text::split_ws(lines[hi].text);
    if (header.size() < 2 || header[0] != "timestamp") text::fail(name, lines[hi].number, "expected a header 'timestamp <sensor>...'");
    int cp = -1;
    if (const auto want = o.text("column")) {
        for (std::size_t i = 1; i < header.size(); ++i)
            if (header[i] == *want) cp = static_cast<int>(i);
        if (cp < 0) throw Error(parser + ": column '" + *want + "' is not in the header");
    } else {
        for (std::size_t i = 1; i < header.size() && cp < 0; ++i)
            if (header[i].find("instant") != std::string_view::npos) cp = static_cast<int>(i);
        if (cp < 0) cp = 1;
    }
    TraceBuilder b(name, "pmt");
    b.power_source("gpu", o);
    b.trace().quantity = std::string(header[cp]);
    b.trace().wall_clock = true;
    // Marker times are relative to PMT's own start, which the dump does not state; each marker's
    // position between two samples bounds that start, and the mean of the bounds is used.
    struct PendingMarker { double rel; std::string label; std::size_t after_sample; std::size_t line; };
    std::vector<PendingMarker> pending;
    bool integral = true;
    for (std::size_t li = hi + 1; li < lines.size(); ++li) {
        const auto& l = lines[li];
        const auto s = text::trim(l.text);
        if (s.empty()) continue;
        if (s.front() == 'M') {
            const auto f = text::split_ws(s);
            const auto rel = f.size() >= 2 ? text::to_number(f[1]) : std::nullopt;
            if (f.size() < 2 || f[0] != "M" || !rel) text::fail(name, l.number, "marker line must be M <seconds> \"label\"");
            std::string label(text::trim(s.substr(s.find(f[1]) + f[1].size())));
            if (label.size() >= 2 && label.front() == '"' && label.back() == '"') label = label.substr(1, label.size() - 2);
            pending.push_back({*rel, label, b.trace().t.size(), l.number});
            continue;
        }
        const auto f = text::split_ws(s);
        if (f.size() != header.size()) text::fail(name, l.number, "expected " + std::to_string(header.size()) + " fields, found " + std::to_string(f.size()));
        const auto t = text::to_number(f[0]);
        const auto w = text::to_number(f[cp]);
        if (!t || !w) text::fail(name, l.number, "timestamp and '" + std::string(header[cp]) + "' must be numbers");
        integral = integral && *w == std::trunc(*w);
        b.add(l.number, *t, *w);
    }
    if (integral) {
        b.trace().resolution_w = 1;
        b.note("every reading is a whole number of watts: resolution 1 W");
    }
    PowerTrace tr = b.finish();
    if (!pending.empty()) {
        double lo = -1e300, hi_bound = 1e300, sum = 0;
        std::size_t n = 0;
        for (const auto& m : pending) {
            if (m.after_sample == 0 || m.after_sample >= tr.size()) continue;
            const double a = tr.t[m.after_sample - 1] - m.rel, c = tr.t[m.after_sample] - m.rel;
            lo = std::max(lo, a);
            hi_bound = std::min(hi_bound, c);
            sum += 0.5 * (a + c);
            ++n;
        }
        if (n == 0) text::fail(name, pending.front().line, "markers lie outside the samples; cannot place them in time");
        const double start = sum / static_cast<double>(n);
        for (const auto& m : pending) tr.markers.push_back({start + m.rel, m.label});
        char buf[240];
        if (lo <= hi_bound)
            std::snprintf(buf, sizeof buf, "%zu marker(s): PMT start placed at %.3f s (consistent window %.4f s wide)", pending.size(), start, hi_bound - lo);
        else
            std::snprintf(buf, sizeof buf, "%zu marker(s): PMT start placed at %.3f s, but marker positions disagree by %.4f s", pending.size(), start, lo - hi_bound);
        tr.notes.push_back(buf);
    }
    return tr;
}

}  // namespace trn::energy
