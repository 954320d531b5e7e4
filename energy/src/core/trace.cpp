#include <algorithm>
#include <cmath>

#include "trn/energy/trace.hpp"
#include "trn/error.hpp"

namespace trn::energy {

SamplingReport describe_sampling(const PowerTrace& trace) {
    SamplingReport r;
    r.samples = trace.size();
    if (trace.size() < 2) return r;
    r.duration_s = trace.t.back() - trace.t.front();
    std::vector<double> dt(trace.size() - 1);
    for (std::size_t i = 1; i < trace.size(); ++i) dt[i - 1] = trace.t[i] - trace.t[i - 1];
    std::vector<double> sorted = dt;
    std::nth_element(sorted.begin(), sorted.begin() + sorted.size() / 2, sorted.end());
    r.median_dt_s = sorted[sorted.size() / 2];
    r.rate_hz = r.median_dt_s > 0 ? 1.0 / r.median_dt_s : 0;
    for (std::size_t i = 0; i < dt.size(); ++i) {
        if (dt[i] > 3 * r.median_dt_s) ++r.gaps;
        r.longest_gap_s = std::max(r.longest_gap_s, dt[i]);
        if (trace.w[i + 1] == trace.w[i]) ++r.stale_repeats;
    }
    return r;
}

void validate_trace(const PowerTrace& trace) {
    const std::string& name = trace.source.empty() ? std::string("power trace") : trace.source;
    if (trace.t.size() != trace.w.size()) throw Error(name + ": time and power columns differ in length");
    if (trace.size() < 2) throw Error(name + ": fewer than two usable samples (" + std::to_string(trace.size()) + ")");
    for (std::size_t i = 0; i < trace.size(); ++i) {
        if (!std::isfinite(trace.t[i]) || !std::isfinite(trace.w[i]))
            throw Error(name + ": sample " + std::to_string(i) + " is not finite");
        if (i > 0 && !(trace.t[i] > trace.t[i - 1]))
            throw Error(name + ": sample " + std::to_string(i) + " does not come after the one before it");
    }
}

}  // namespace trn::energy

namespace trn::energy {

const std::vector<PowerSource>& power_sources() {
    static const std::vector<PowerSource> sources = {
        {"rail", 1000, true, "an INA2xx/INA3221 rail (bidirectional shunt)", 0},
        {"gpu", 2000, false, "a GPU board", 1},
        {"cpu", 2000, false, "a CPU package (RAPL energy counter)", 0},
        {"soc", 300, false, "a Jetson module", 0.5},
        {"usb", 240, true, "a USB-powered device", 0},
        {"node", 20000, true, "a computer or a server node (meter, BMC)", 0.5},
        {"rack", 500000, true, "a rack", 50},
    };
    return sources;
}

const PowerSource& power_source(const std::string& name) {
    std::string list;
    for (const auto& s : power_sources()) {
        if (s.name == name) return s;
        list += (list.empty() ? "" : ", ") + s.name;
    }
    throw Error("option source='" + name + "': unknown (known: " + list + ")");
}

}  // namespace trn::energy
