// Energy integration from Python: the same request the CLI builds from its options, the run
// report's frames as NumPy arrays (python/trnkit/_energy.py has the public function).
#include "py_energy.hpp"

#include <pybind11/numpy.h>
#include <pybind11/stl.h>

#include <map>
#include <string>
#include <vector>

#include "trn/energy/run_report.hpp"

namespace trn::py {
namespace {

namespace pyb = pybind11;

energy::IntegrateRequest request(const std::string& align, double offset, double search, bool insist, const std::string& clock,
                                 const std::string& rule, std::size_t min_samples) {
    energy::IntegrateRequest q;
    if (align == "same-clock") q.align = energy::AlignMode::SameClock;
    else if (align == "offset") q.align = energy::AlignMode::Offset;
    else if (align == "auto") q.align = energy::AlignMode::Auto;
    else throw pyb::value_error("align '" + align + "': expected same-clock, offset or auto");
    if (clock != "real" && clock != "mono") throw pyb::value_error("clock '" + clock + "': expected real or mono");
    if (rule != "trapezoid" && rule != "hold") throw pyb::value_error("rule '" + rule + "': expected trapezoid or hold");
    q.offset_s = offset, q.search_s = search, q.insist = insist;
    q.realtime = clock == "real";
    q.integration.rule = rule == "hold" ? energy::Rule::Hold : energy::Rule::Trapezoid;
    q.integration.min_samples = min_samples;
    return q;
}

template <typename T, typename Field>
pyb::array_t<T> column(const std::vector<energy::ReportFrame>& frames, Field field) {
    pyb::array_t<T> out(static_cast<pyb::ssize_t>(frames.size()));
    T* p = out.mutable_data();
    for (std::size_t i = 0; i < frames.size(); ++i) p[i] = static_cast<T>(field(frames[i].energy));
    return out;
}

pyb::dict integrate(const std::string& log, const std::string& markers, const std::string& format,
                    const std::map<std::string, std::string>& options, const std::string& align, double offset, double search,
                    bool insist, const std::string& clock, const std::string& rule, std::size_t min_samples) {
    const energy::IntegrateRequest q = request(align, offset, search, insist, clock, rule, min_samples);
    energy::RunReport r;
    {
        pyb::gil_scoped_release nogil;
        r = energy::integrate_files(log, format, options, markers, q);
    }
    using F = energy::FrameEnergy;
    pyb::dict out;
    out["id"] = column<std::int32_t>(r.frames, [](const F& f) { return f.id; });
    out["start_s"] = column<double>(r.frames, [](const F& f) { return f.start; });
    out["end_s"] = column<double>(r.frames, [](const F& f) { return f.end; });
    out["gross_j"] = column<double>(r.frames, [](const F& f) { return f.gross_j; });
    out["net_j"] = column<double>(r.frames, [](const F& f) { return f.net_j; });
    out["error_j"] = column<double>(r.frames, [](const F& f) { return f.error_j; });
    out["samples"] = column<std::uint64_t>(r.frames, [](const F& f) { return f.samples; });
    out["usable"] = column<bool>(r.frames, [](const F& f) { return f.flag.empty(); });
    pyb::list flags;
    for (const auto& f : r.frames) flags.append(f.energy.flag);
    out["flag"] = flags;
    out["platform"] = r.platform;
    out["idle_w"] = r.idle_w;
    out["offset_s"] = r.alignment.mapping.offset_s;
    out["drift"] = r.alignment.mapping.drift;
    out["align"] = r.align_mode;
    out["warnings"] = r.warnings;
    return out;
}

}  // namespace

void register_energy(pyb::module_& m) {
    m.def("integrate_energy", &integrate, pyb::arg("log"), pyb::arg("markers"), pyb::arg("format"), pyb::arg("options"),
          pyb::arg("align"), pyb::arg("offset"), pyb::arg("search"), pyb::arg("insist"), pyb::arg("clock"), pyb::arg("rule"),
          pyb::arg("min_samples"));
}

}  // namespace trn::py
