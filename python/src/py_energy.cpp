// Energy from Python: live power sources polled on a sampler thread, measurement windows around
// the caller's own work, and the integration step (files or those objects) as NumPy arrays. The
// public names and docstrings are python/trnkit/_energy.py's; these are the primitives.
#include "py_energy.hpp"

#include <pybind11/numpy.h>
#include <pybind11/stl.h>

#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "trn/energy/background_sampler.hpp"
#include "trn/energy/measurement_window.hpp"
#include "trn/energy/power_sampler.hpp"
#include "trn/energy/run_report.hpp"
#include "trn/error.hpp"
#include "trn/io/atomic_file.hpp"

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

energy::SampleClock sample_clock(const std::string& clock) {
    if (clock == "real") return energy::SampleClock::Realtime;
    if (clock == "mono") return energy::SampleClock::Monotonic;
    throw pyb::value_error("clock '" + clock + "': expected real or mono");
}

template <typename T>
pyb::array_t<T> vector_array(const std::vector<T>& v) {
    pyb::array_t<T> out(static_cast<pyb::ssize_t>(v.size()));
    std::copy(v.begin(), v.end(), out.mutable_data());
    return out;
}

template <typename T, typename Field>
pyb::array_t<T> column(const std::vector<energy::ReportFrame>& frames, Field field) {
    pyb::array_t<T> out(static_cast<pyb::ssize_t>(frames.size()));
    T* p = out.mutable_data();
    for (std::size_t i = 0; i < frames.size(); ++i) p[i] = static_cast<T>(field(frames[i]));
    return out;
}

// A live source and, while started, the thread polling it (destroyed first: it holds a reference).
struct PySampler {
    std::unique_ptr<energy::PowerSampler> source;
    std::unique_ptr<energy::BackgroundSampler> thread;
    std::string description;
};

energy::PowerTrace stop(PySampler& s) {
    if (!s.thread) throw Error("power sampler " + s.description + " is not running (start() it first)");
    auto thread = std::move(s.thread);
    pyb::gil_scoped_release nogil;
    return thread->stop();  // rethrows the thread's error, naming the source
}

pyb::dict report_dict(const energy::RunReport& r) {
    using F = energy::ReportFrame;
    pyb::dict out;
    out["id"] = column<std::int32_t>(r.frames, [](const F& f) { return f.energy.id; });
    out["start_s"] = column<double>(r.frames, [](const F& f) { return f.energy.start; });
    out["end_s"] = column<double>(r.frames, [](const F& f) { return f.energy.end; });
    out["gross_j"] = column<double>(r.frames, [](const F& f) { return f.energy.gross_j; });
    out["net_j"] = column<double>(r.frames, [](const F& f) { return f.energy.net_j; });
    out["error_j"] = column<double>(r.frames, [](const F& f) { return f.energy.error_j; });
    out["samples"] = column<std::uint64_t>(r.frames, [](const F& f) { return f.energy.samples; });
    out["usable"] = column<bool>(r.frames, [](const F& f) { return f.energy.flag.empty(); });
    out["marker_ms"] = column<double>(r.frames, [](const F& f) { return f.marker_ms; });
    out["write_ms"] = column<double>(r.frames, [](const F& f) { return f.write_ms; });
    out["exec_ms"] = column<double>(r.frames, [](const F& f) { return f.exec_ms; });
    out["read_ms"] = column<double>(r.frames, [](const F& f) { return f.read_ms; });
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

// log: a path or a PowerTrace; markers: a path, "" (the log's own start/end markers) or MeasurementWindows.
pyb::dict integrate(const pyb::object& log, const pyb::object& markers, const std::string& format,
                    const std::map<std::string, std::string>& options, const std::string& align, double offset, double search,
                    bool insist, const std::string& clock, const std::string& rule, std::size_t min_samples) {
    const energy::IntegrateRequest q = request(align, offset, search, insist, clock, rule, min_samples);
    const bool log_is_path = pyb::isinstance<pyb::str>(log), markers_are_path = pyb::isinstance<pyb::str>(markers);
    if (!markers_are_path && markers.cast<const energy::MeasurementWindows&>().open())
        throw Error("integrate_energy: a measurement window is still open (end it first)");
    energy::RunReport r;
    if (log_is_path && markers_are_path) {
        const auto log_path = log.cast<std::string>(), markers_path = markers.cast<std::string>();
        {
            pyb::gil_scoped_release nogil;
            r = energy::integrate_files(log_path, format, options, markers_path, q);
        }
        return report_dict(r);
    }
    std::optional<energy::PowerTrace> read_trace;
    const energy::PowerTrace* trace = nullptr;
    if (log_is_path) {
        const auto path = log.cast<std::string>();
        pyb::gil_scoped_release nogil;
        read_trace = energy::read_power_log(path, format, options);
        trace = &*read_trace;
    } else {
        trace = &log.cast<const energy::PowerTrace&>();
    }
    energy::MarkerFile marker_file;
    if (markers_are_path) {
        const auto path = markers.cast<std::string>();
        marker_file = path.empty() ? energy::markers_from_trace(*trace) : energy::read_markers(path);
    } else {
        marker_file = markers.cast<const energy::MeasurementWindows&>().markers();
    }
    {
        pyb::gil_scoped_release nogil;
        r = energy::integrate_run(*trace, marker_file, q);
    }
    return report_dict(r);
}

}  // namespace

void register_energy(pyb::module_& m) {
    m.def("integrate_energy", &integrate, pyb::arg("log"), pyb::arg("markers"), pyb::arg("format"), pyb::arg("options"),
          pyb::arg("align"), pyb::arg("offset"), pyb::arg("search"), pyb::arg("insist"), pyb::arg("clock"), pyb::arg("rule"),
          pyb::arg("min_samples"));

    pyb::class_<energy::PowerTrace>(m, "PowerTrace", "Power samples of one source: t (s), w (W), with the source's notes.")
        .def_readonly("source", &energy::PowerTrace::source)
        .def_readonly("format", &energy::PowerTrace::format)
        .def_readonly("quantity", &energy::PowerTrace::quantity)
        .def_readonly("wall_clock", &energy::PowerTrace::wall_clock)
        .def_property_readonly("kind", [](const energy::PowerTrace& t) {
            return t.kind == energy::SampleKind::Instant ? "instant" : "interval-mean";
        })
        .def_property_readonly("t", [](const energy::PowerTrace& t) { return vector_array(t.t); })
        .def_property_readonly("w", [](const energy::PowerTrace& t) { return vector_array(t.w); })
        .def_readonly("notes", &energy::PowerTrace::notes)
        .def_readonly("warnings", &energy::PowerTrace::warnings)
        .def("__len__", &energy::PowerTrace::size)
        .def("_save", [](const energy::PowerTrace& t, const std::string& path) {
            const std::string text = energy::format_trnkit_power(t);
            pyb::gil_scoped_release nogil;
            io::write_file_atomic(path, text);
        })
        .def("__repr__", [](const energy::PowerTrace& t) {
            return "<trnkit.PowerTrace " + std::to_string(t.size()) + " samples of " + t.source + (t.wall_clock ? ", wall clock" : "") + ">";
        });

    m.def("power_sources", &energy::list_power_sources, pyb::arg("options"));
    pyb::class_<energy::SamplerOptions>(m, "SamplerOptions")
        .def(pyb::init([](std::string sysfs_root, std::string nvml_library, std::string vcgencmd) {
                 return energy::SamplerOptions{std::move(sysfs_root), std::move(nvml_library), std::move(vcgencmd)};
             }),
             pyb::arg("sysfs_root"), pyb::arg("nvml_library"), pyb::arg("vcgencmd") = energy::SamplerOptions{}.vcgencmd);

    pyb::class_<PySampler>(m, "PowerSampler")
        .def(pyb::init([](const std::string& spec, const energy::SamplerOptions& options) {
                 auto s = std::make_unique<PySampler>();
                 pyb::gil_scoped_release nogil;
                 s->source = energy::make_power_sampler(spec, options);
                 s->description = s->source->describe();
                 return s;
             }),
             pyb::arg("spec"), pyb::arg("options"))
        .def_property_readonly("description", [](const PySampler& s) { return s.description; })
        .def_property_readonly("running", [](const PySampler& s) { return s.thread != nullptr; })
        .def_property_readonly("late_polls", [](const PySampler& s) { return s.thread ? s.thread->late_polls() : std::size_t(0); })
        .def(
            "_start",
            [](PySampler& s, double period_s, const std::string& clock) {
                if (s.thread) throw Error("power sampler " + s.description + " is already running");
                const energy::SampleClock c = sample_clock(clock);
                pyb::gil_scoped_release nogil;
                s.thread = std::make_unique<energy::BackgroundSampler>(*s.source, period_s, c);  // polls once now
            },
            pyb::arg("period_s"), pyb::arg("clock"))
        .def("_stop", &stop)
        .def(
            "_sample",
            [](PySampler& s, double period_s, double duration_s, const std::string& clock) {
                if (s.thread) throw Error("power sampler " + s.description + " is running; stop() it before sample()");
                if (!(period_s > 0)) throw pyb::value_error("period_s must be > 0");
                if (!(duration_s >= 0)) throw pyb::value_error("duration_s must be >= 0");
                const energy::SampleClock c = sample_clock(clock);
                pyb::gil_scoped_release nogil;
                return energy::sample_for(*s.source, period_s, duration_s, c);
            },
            pyb::arg("period_s"), pyb::arg("duration_s"), pyb::arg("clock"));

    using W = energy::MeasurementWindows;
    pyb::class_<W>(m, "MeasurementWindows")
        .def(pyb::init<std::map<std::string, std::string>>(), pyb::arg("meta"))
        .def("_begin_frame", &W::begin_frame)
        .def("_end_frame", &W::end_frame, pyb::arg("write_ms"), pyb::arg("exec_ms"), pyb::arg("read_ms"))
        .def("_begin_idle", &W::begin_idle)
        .def("_end_idle", &W::end_idle)
        .def("_idle_for", &W::idle_for, pyb::arg("seconds"), pyb::call_guard<pyb::gil_scoped_release>())
        .def_property_readonly("open", &W::open)
        .def_property_readonly("frames", &W::frames)
        .def("_rows", [](const W& w) {
            pyb::list out;
            for (const auto& r : w.markers().rows)
                out.append(pyb::make_tuple(r.kind, r.id, r.mono_start_ns, r.mono_end_ns, r.real_start_ns, r.real_end_ns));
            return out;
        })
        .def("_save", &W::save, pyb::arg("path"), pyb::call_guard<pyb::gil_scoped_release>())
        .def("_save_minimal", &W::save_minimal, pyb::arg("path"), pyb::arg("realtime"), pyb::call_guard<pyb::gil_scoped_release>());
}

}  // namespace trn::py
