// The scorer from Python: devices, backends, maps, plans, scoring and Sobel. Device work runs with
// the GIL released; each backend has a mutex because a trn::Backend is not thread-safe.
#include "py_backend.hpp"

#include <pybind11/numpy.h>
#include <pybind11/stl.h>

#include <memory>
#include <mutex>
#include <string>
#include <vector>

#include "py_arrays.hpp"
#include "trn/registry.hpp"

namespace trn::py {
namespace {

struct PyBackend {
    std::unique_ptr<Backend> impl;
    std::mutex mutex;
};

// A map keeps its backend alive (declared first: released after the map).
struct PyMap {
    std::shared_ptr<PyBackend> backend;
    MapHandle handle;
};

pyb::dict device_dict(const DeviceInfo& d) {
    pyb::dict out;
    out["name"] = d.name, out["family"] = d.family, out["device"] = d.device;
    out["type"] = d.type, out["driver"] = d.driver, out["details"] = d.details;
    return out;
}

ScoreOptions score_options(const pyb::object& sampling, double min_valid_fraction) {
    ScoreOptions o;
    if (!sampling.is_none()) {
        if (!pyb::isinstance<Sampling>(sampling))
            throw pyb::type_error("sampling must be a trnkit.Sampling (Sampling.dense(), .random(fraction, seed), .explicit(points)) or None");
        o.sampling = sampling.cast<Sampling>();
    }
    o.min_valid_fraction = min_valid_fraction;
    return o;
}

ScoringPlan make_plan(const pyb::handle& templ, const pyb::object& sampling, double min_valid_fraction) {
    const BorrowedTemplate t = template_view(templ, "template");
    const ScoreOptions o = score_options(sampling, min_valid_fraction);
    pyb::gil_scoped_release nogil;
    return make_scoring_plan(t.view, o);
}

pyb::array score(PyBackend& self, const PyMap& map, const pyb::handle& templ, const pyb::handle& poses_arg, const pyb::object& sampling,
                 double min_valid_fraction) {
    const std::vector<Pose> poses = poses_from(poses_arg);
    pyb::array_t<ParticleScore> out(static_cast<pyb::ssize_t>(poses.size()));
    const std::span<ParticleScore> scores(out.mutable_data(), poses.size());
    if (pyb::isinstance<ScoringPlan>(templ)) {
        if (!sampling.is_none()) throw pyb::value_error("sampling is part of the plan; pass it to trnkit.plan(), not to score()");
        const ScoringPlan& plan = templ.cast<const ScoringPlan&>();
        pyb::gil_scoped_release nogil;
        std::lock_guard lock(self.mutex);
        self.impl->score(map.handle, plan, poses, scores);
    } else {
        const BorrowedTemplate t = template_view(templ, "template");
        const ScoreOptions o = score_options(sampling, min_valid_fraction);
        pyb::gil_scoped_release nogil;
        std::lock_guard lock(self.mutex);
        self.impl->score(map.handle, t.view, poses, o, scores);
    }
    return out;
}

pyb::tuple sobel(PyBackend& self, const pyb::handle& image) {
    const BorrowedGray src = gray_view(image, "image");
    const auto h = static_cast<pyb::ssize_t>(src.view.height), w = static_cast<pyb::ssize_t>(src.view.width);
    pyb::array_t<std::int16_t> gx({h, w}), gy({h, w});
    const Int16View vx{gx.mutable_data(), src.view.width, src.view.height, src.view.width};
    const Int16View vy{gy.mutable_data(), src.view.width, src.view.height, src.view.width};
    {
        pyb::gil_scoped_release nogil;
        std::lock_guard lock(self.mutex);
        self.impl->sobel(src.view, vx, vy);
    }
    return pyb::make_tuple(gx, gy);
}

}  // namespace

void register_backend(pyb::module_& m) {
    // ParticleScore's own memory is the structured array's: scores are written in place.
    PYBIND11_NUMPY_DTYPE(ParticleScore, ncc, cc, ssd, valid_samples, flags);
    m.attr("TOO_FEW_SAMPLES") = static_cast<std::uint32_t>(kTooFewSamples);
    m.attr("FLAT_PATCH") = static_cast<std::uint32_t>(kFlatPatch);
    m.attr("FLAT_TEMPLATE") = static_cast<std::uint32_t>(kFlatTemplate);
    m.attr("SCORE_DTYPE") = pyb::dtype::of<ParticleScore>();

    m.def(
        "devices",
        [] {
            std::vector<FamilyStatus> families;
            {
                pyb::gil_scoped_release nogil;
                families = default_registry().status();
            }
            pyb::list out;
            for (const auto& f : families)
                for (const auto& d : f.devices) out.append(device_dict(d));
            return out;
        },
        "Every usable device of every backend family this build has, as dicts (name, family, device, type, driver, details).");

    pyb::class_<Sampling>(m, "Sampling", "Which template pixels take part in the score (trn/scoring.hpp).")
        .def_static("dense", &Sampling::dense, "Every template pixel.")
        .def_static("random", &Sampling::random, pyb::arg("fraction"), pyb::arg("seed") = 1,
                    "A share in (0, 1] of the template pixels; the same seed picks the same pixels on every backend.")
        .def_static(
            "explicit",
            [](const pyb::handle& points) {
                auto a = pyb::array_t<std::int32_t, pyb::array::c_style | pyb::array::forcecast>::ensure(points);
                if (!a || a.ndim() != 2 || a.shape(1) != 2) {
                    PyErr_Clear();
                    throw pyb::value_error("points must be an integer array of shape (K, 2): u, v template pixels");
                }
                std::vector<SamplePoint> pts(static_cast<std::size_t>(a.shape(0)));
                for (std::size_t i = 0; i < pts.size(); ++i) pts[i] = {a.data()[2 * i], a.data()[2 * i + 1]};
                return Sampling::explicit_points(std::move(pts));
            },
            pyb::arg("points"), "These (u, v) template pixels, an integer array of shape (K, 2).")
        .def("__repr__", [](const Sampling& s) {
            if (s.kind == Sampling::Kind::Dense) return std::string("Sampling.dense()");
            if (s.kind == Sampling::Kind::Random)
                return "Sampling.random(" + std::to_string(s.fraction) + ", " + std::to_string(s.seed) + ")";
            return "Sampling.explicit(" + std::to_string(s.points.size()) + " points)";
        });

    pyb::class_<ScoringPlan>(m, "Plan", "A template prepared for scoring (once per camera frame).")
        .def_property_readonly("sample_count", &ScoringPlan::sample_count)
        .def_readonly("width", &ScoringPlan::width)
        .def_readonly("height", &ScoringPlan::height);
    m.def("plan", &make_plan, pyb::arg("template"), pyb::arg("sampling") = pyb::none(), pyb::arg("min_valid_fraction") = 0.9,
          "Validates a template (2-D uint8 or float) and its sampling and prepares it for Backend.score.");

    pyb::class_<PyMap, std::shared_ptr<PyMap>>(m, "Map", "A map uploaded to one backend (Backend.upload_map).")
        .def_property_readonly("width", [](const PyMap& p) { return p.handle->width(); })
        .def_property_readonly("height", [](const PyMap& p) { return p.handle->height(); })
        .def_property_readonly("backend", [](const PyMap& p) { return p.backend->impl->info().name; });

    pyb::class_<PyBackend, std::shared_ptr<PyBackend>>(m, "Backend", "One compute backend: cpu-ref, cpu, opencl[:N|:name], vulkan[:N|:name].")
        .def(pyb::init([](const std::string& spec) {
                 auto b = std::make_shared<PyBackend>();
                 pyb::gil_scoped_release nogil;  // creating a GPU backend compiles or loads its programs
                 b->impl = default_registry().create(spec);
                 return b;
             }),
             pyb::arg("spec"), "Creates the backend or raises BackendUnavailable saying why (never a fallback).")
        .def_property_readonly("name", [](const PyBackend& b) { return b.impl->info().name; })
        .def_property_readonly("info", [](const PyBackend& b) { return device_dict(b.impl->info()); })
        .def(
            "upload_map",
            [](const std::shared_ptr<PyBackend>& self, const pyb::handle& image) {
                const BorrowedGray map = gray_view(image, "map");
                auto out = std::make_shared<PyMap>();
                out->backend = self;
                pyb::gil_scoped_release nogil;
                std::lock_guard lock(self->mutex);
                out->handle = self->impl->upload_map(map.view);
                return out;
            },
            pyb::arg("map"), "Copies a 2-D uint8 map to the backend (read in place when its rows are contiguous).")
        .def("score", &score, pyb::arg("map"), pyb::arg("template"), pyb::arg("poses"), pyb::arg("sampling") = pyb::none(),
             pyb::arg("min_valid_fraction") = 0.9,
             "Scores poses (N, 4: x, y, yaw, scale) against a template (2-D uint8/float array or a Plan); returns a "
             "structured array of N (ncc, cc, ssd, valid_samples, flags).")
        .def("sobel", &sobel, pyb::arg("image"), "3x3 Sobel of a 2-D uint8 image: (gx, gy) int16 arrays, bit-exact with cv::Sobel.")
        .def("__repr__", [](const PyBackend& b) { return "trnkit.Backend('" + b.impl->info().name + "')"; });
}

}  // namespace trn::py
