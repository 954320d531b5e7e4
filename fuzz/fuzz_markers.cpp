// Fuzz entry: the frame-marker file of `trnkit frames` (energy/src/core/markers.cpp). What the parser
// accepts must be well-formed (end >= start, finite phase times), map to finite intervals on
// both clocks, and survive format_markers -> parse_markers unchanged (phase times to the 1e-6 ms
// that the writer keeps).
#include <cmath>

#include "fuzz_check.hpp"
#include "trn/energy/markers.hpp"
#include "trn/error.hpp"

namespace {

bool same_ms(double a, double b) { return std::fabs(a - b) <= 5e-7 + 1e-15 * std::fabs(a); }

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    using trn::fuzz::require;
    namespace en = trn::energy;
    en::MarkerFile m;
    try {
        m = en::parse_markers(trn::fuzz::as_text(data, size), "fuzz.csv");
    } catch (const trn::Error&) {
        return 0;
    }
    for (const auto& r : m.rows) {
        require(r.kind == "sync" || r.kind == "idle" || r.kind == "frame", "unknown kind accepted");
        require(r.mono_end_ns >= r.mono_start_ns && r.real_end_ns >= r.real_start_ns, "end before start accepted");
        require(std::isfinite(r.write_ms) && std::isfinite(r.exec_ms) && std::isfinite(r.read_ms), "non-finite phase time accepted");
    }
    for (bool realtime : {true, false})
        for (const auto& iv : en::marker_intervals(m, en::ClockMapping{realtime}))
            require(std::isfinite(iv.start) && std::isfinite(iv.end) && iv.end >= iv.start, "bad interval from accepted markers");
    const en::MarkerFile back = en::parse_markers(en::format_markers(m), "round-trip.csv");  // our own output must parse
    for (const auto& [k, v] : m.meta)
        for (const char c : k + v) require(static_cast<unsigned char>(c) >= 0x20 && c != 0x7f, "a control character accepted in the header");
    require(back.meta == m.meta, "round trip changed the header");
    require(back.rows.size() == m.rows.size(), "round trip changed the row count");
    for (std::size_t i = 0; i < m.rows.size(); ++i) {
        const auto &a = m.rows[i], &b = back.rows[i];
        require(a.kind == b.kind && a.id == b.id && a.mono_start_ns == b.mono_start_ns && a.mono_end_ns == b.mono_end_ns &&
                    a.real_start_ns == b.real_start_ns && a.real_end_ns == b.real_end_ns,
                "round trip changed a row");
        require(same_ms(a.write_ms, b.write_ms) && same_ms(a.exec_ms, b.exec_ms) && same_ms(a.read_ms, b.read_ms),
                "round trip changed a phase time");
    }
    return 0;
}
