// The scorer from Python: devices, backends, maps, plans, scoring and Sobel. Device work runs with
// the GIL released; each backend has a mutex because a trn::Backend is not thread-safe. The public
// names (keywords, docstrings, warnings) are python/trnkit/_backend.py's; these are the primitives.
#include "py_backend.hpp"

#include <optional>
#include <pybind11/numpy.h>
#include <pybind11/stl.h>

#include <string>
#include <vector>

#include "py_arrays.hpp"
#include "trn/registry.hpp"

namespace trn::py {

namespace pyb = pybind11;

Backend& PyBackend::open_backend() const {
    if (!impl) throw Error("backend '" + name + "' is closed");
    return *impl;
}

const MapHandle& PyMap::open_handle() const {
    if (!handle) throw Error("the map was released when its backend '" + backend->name + "' was closed");
    return handle;
}

namespace {

pyb::dict device_dict(const DeviceInfo& d) {
    pyb::dict out;
    out["name"] = d.name, out["family"] = d.family, out["device"] = d.device;
    out["type"] = d.type, out["driver"] = d.driver, out["details"] = d.details;
    return out;
}

pyb::tuple times_tuple(const PhaseTimes& t) { return pyb::make_tuple(t.upload_ms, t.execute_ms, t.download_ms); }

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

// `out` when it is an array scores can be written into in place, else a new one.
pyb::array_t<ParticleScore> score_array(const pyb::object& out, std::size_t n) {
    if (out.is_none()) return pyb::array_t<ParticleScore>(static_cast<pyb::ssize_t>(n));
    const std::string want = "out must be a writeable C-contiguous numpy array of dtype trnkit.SCORE_DTYPE and shape (" +
                             std::to_string(n) + ",), one entry per pose";
    if (!pyb::isinstance<pyb::array>(out)) throw pyb::type_error(want + "; got " + std::string(pyb::str(out.get_type().attr("__name__"))));
    auto a = pyb::reinterpret_borrow<pyb::array>(out);
    if (!a.dtype().equal(pyb::dtype::of<ParticleScore>()))
        throw pyb::value_error(want + "; got dtype " + std::string(pyb::str(a.dtype())));
    if (a.ndim() != 1 || a.shape(0) != static_cast<pyb::ssize_t>(n))
        throw pyb::value_error(want + "; got shape " + std::string(pyb::str(out.attr("shape"))));
    if (!(a.flags() & pyb::array::c_style) || !a.writeable()) throw pyb::value_error(want + "; got a read-only or strided array");
    return pyb::reinterpret_borrow<pyb::array_t<ParticleScore>>(out);
}

pyb::object score(PyBackend& self, const PyMap& map, const pyb::handle& templ, const pyb::handle& poses_arg, const pyb::object& sampling,
                  double min_valid_fraction, const pyb::object& out_arg, bool want_times) {
    const std::vector<Pose> poses = poses_from(poses_arg);
    pyb::array_t<ParticleScore> out = score_array(out_arg, poses.size());
    const std::span<ParticleScore> scores(out.mutable_data(), poses.size());
    PhaseTimes times;
    if (pyb::isinstance<ScoringPlan>(templ)) {
        if (!sampling.is_none()) throw pyb::value_error("sampling is part of the plan; pass it to trnkit.plan(), not to score()");
        const ScoringPlan& plan = templ.cast<const ScoringPlan&>();
        pyb::gil_scoped_release nogil;
        std::lock_guard lock(self.mutex);
        self.open_backend().score(map.open_handle(), plan, poses, scores, &times);
    } else {
        const BorrowedTemplate t = template_view(templ, "template");
        const ScoreOptions o = score_options(sampling, min_valid_fraction);
        pyb::gil_scoped_release nogil;
        std::lock_guard lock(self.mutex);
        self.open_backend().score(map.open_handle(), t.view, poses, o, scores, &times);
    }
    if (want_times) return pyb::make_tuple(out, times_tuple(times));
    return out;
}

pyb::object sobel(PyBackend& self, const pyb::handle& image, bool want_times) {
    const BorrowedGray src = gray_view(image, "image");
    const auto h = static_cast<pyb::ssize_t>(src.view.height), w = static_cast<pyb::ssize_t>(src.view.width);
    pyb::array_t<std::int16_t> gx({h, w}), gy({h, w});
    const Int16View vx{gx.mutable_data(), src.view.width, src.view.height, src.view.width};
    const Int16View vy{gy.mutable_data(), src.view.width, src.view.height, src.view.width};
    PhaseTimes times;
    {
        pyb::gil_scoped_release nogil;
        std::lock_guard lock(self.mutex);
        self.open_backend().sobel(src.view, vx, vy, &times);
    }
    if (want_times) return pyb::make_tuple(gx, gy, times_tuple(times));
    return pyb::make_tuple(gx, gy);
}

pyb::object upload_map(const std::shared_ptr<PyBackend>& self, const pyb::handle& image, const pyb::handle& valid, bool want_times) {
    const BorrowedGray map = gray_view(image, "map");
    const std::optional<BorrowedGray> mask = valid.is_none() ? std::nullopt : std::optional<BorrowedGray>(gray_view(valid, "valid"));
    auto out = std::make_shared<PyMap>();
    out->backend = self;
    out->width = map.view.width, out->height = map.view.height;
    PhaseTimes times;
    {
        pyb::gil_scoped_release nogil;
        std::lock_guard lock(self->mutex);
        out->handle = self->open_backend().upload_map(map.view, mask ? mask->view : GrayView{}, &times);
        std::erase_if(self->maps, [](const std::weak_ptr<PyMap>& m) { return m.expired(); });
        self->maps.push_back(out);
    }
    if (want_times) return pyb::make_tuple(out, times_tuple(times));
    return pyb::cast(out);
}

// Releases the localizers' and the maps' device memory, then the backend; idempotent.
void close(PyBackend& self) {
    std::vector<MapHandle> released;  // destroyed after the lock, with the GIL released
    std::unique_ptr<Backend> impl;
    pyb::gil_scoped_release nogil;
    {
        std::lock_guard lock(self.mutex);
        for (const auto& weak : self.users)
            if (auto u = weak.lock()) u->release_device();
        self.users.clear();
        for (const auto& weak : self.maps)
            if (auto m = weak.lock()) released.push_back(std::move(m->handle));
        self.maps.clear();
        released.clear();
        impl = std::move(self.impl);
    }
}

std::shared_ptr<PyBackend> create(const std::string& spec, int threads, bool simd, const std::string& opencl_device,
                                  const std::string& vulkan_device, std::uint32_t opencl_work_group, std::uint32_t vulkan_work_group,
                                  const std::string& opencl_cache_dir, const std::string& vulkan_cache_dir,
                                  std::uint32_t particles_per_group, bool quad_maps, bool subgroups, bool force_staging, bool validation) {
    BackendOptions o;
    if (!opencl_device.empty()) o.default_device["opencl"] = opencl_device;
    if (!vulkan_device.empty()) o.default_device["vulkan"] = vulkan_device;
    o.cpu.threads = threads, o.cpu.simd = simd;
    o.opencl.work_group = opencl_work_group, o.opencl.program_cache_dir = opencl_cache_dir;
    o.vulkan.work_group = vulkan_work_group, o.vulkan.particles_per_group = particles_per_group;
    o.vulkan.quad_maps = quad_maps, o.vulkan.subgroups = subgroups, o.vulkan.force_staging = force_staging;
    o.vulkan.validation = validation, o.vulkan.pipeline_cache_dir = vulkan_cache_dir;
    auto b = std::make_shared<PyBackend>();
    pyb::gil_scoped_release nogil;  // creating a GPU backend compiles or loads its programs
    b->impl = default_registry().create(spec, o);
    b->name = b->impl->info().name;
    return b;
}

}  // namespace

void register_backend(pyb::module_& m) {
    // ParticleScore's own memory is the structured array's: scores are written in place.
    PYBIND11_NUMPY_DTYPE(ParticleScore, ncc, cc, ssd, valid_samples, flags);
    m.attr("TOO_FEW_SAMPLES") = static_cast<std::uint32_t>(kTooFewSamples);
    m.attr("FLAT_PATCH") = static_cast<std::uint32_t>(kFlatPatch);
    m.attr("FLAT_TEMPLATE") = static_cast<std::uint32_t>(kFlatTemplate);
    m.attr("SCORE_DTYPE") = pyb::dtype::of<ParticleScore>();

    m.def("devices", [] {
        std::vector<FamilyStatus> families;
        {
            pyb::gil_scoped_release nogil;
            families = default_registry().status();
        }
        pyb::list out;
        for (const auto& f : families)
            for (const auto& d : f.devices) out.append(device_dict(d));
        return out;
    });
    m.def("families", [] {
        std::vector<std::string> out;
        for (const auto& f : default_registry().families()) out.push_back(f.name);
        return out;
    });

    pyb::class_<Sampling>(m, "Sampling", "Which template pixels take part in the score (trn/scoring.hpp).")
        .def_static("_dense", &Sampling::dense)
        .def_static("_random", &Sampling::random, pyb::arg("fraction"), pyb::arg("seed"))
        .def_static("_explicit",
                    [](const pyb::handle& points) {
                        auto a = pyb::array_t<std::int32_t, pyb::array::c_style | pyb::array::forcecast>::ensure(points);
                        if (!a || a.ndim() != 2 || a.shape(1) != 2) {
                            PyErr_Clear();
                            throw pyb::value_error("points must be an integer array of shape (K, 2): u, v template pixels");
                        }
                        std::vector<SamplePoint> pts(static_cast<std::size_t>(a.shape(0)));
                        for (std::size_t i = 0; i < pts.size(); ++i) pts[i] = {a.data()[2 * i], a.data()[2 * i + 1]};
                        return Sampling::explicit_points(std::move(pts));
                    })
        .def_property_readonly("kind", [](const Sampling& s) {
            return s.kind == Sampling::Kind::Dense ? "dense" : s.kind == Sampling::Kind::Random ? "random" : "explicit";
        })
        .def("__repr__", [](const Sampling& s) {
            if (s.kind == Sampling::Kind::Dense) return std::string("Sampling.dense()");
            if (s.kind == Sampling::Kind::Random)
                return "Sampling.random(" + std::to_string(s.fraction) + ", " + std::to_string(s.seed) + ")";
            return "Sampling.explicit(" + std::to_string(s.points.size()) + " points)";
        });

    pyb::class_<ScoringPlan>(m, "Plan", "A template prepared for scoring (once per camera frame): trnkit.plan().")
        .def_property_readonly("sample_count", &ScoringPlan::sample_count)
        .def_readonly("width", &ScoringPlan::width)
        .def_readonly("height", &ScoringPlan::height)
        .def("__repr__", [](const ScoringPlan& p) {
            return "<trnkit.Plan " + std::to_string(p.width) + "x" + std::to_string(p.height) + ", " + std::to_string(p.sample_count()) +
                   " samples>";
        });
    m.def("plan", &make_plan, pyb::arg("template"), pyb::arg("sampling"), pyb::arg("min_valid_fraction"));

    pyb::class_<PyMap, std::shared_ptr<PyMap>>(m, "Map", "A map uploaded to one backend (Backend.upload_map).")
        .def_property_readonly("width", [](const PyMap& p) { return p.width; })
        .def_property_readonly("height", [](const PyMap& p) { return p.height; })
        .def_property_readonly("backend", [](const PyMap& p) { return p.backend->name; })
        .def("__repr__", [](const PyMap& p) {
            return "<trnkit.Map " + std::to_string(p.width) + "x" + std::to_string(p.height) + " on " + p.backend->name +
                   (p.handle ? "" : ", released") + ">";
        });

    pyb::class_<PyBackend, std::shared_ptr<PyBackend>>(m, "Backend", "The compiled half of trnkit.Backend.")
        .def(pyb::init(&create), pyb::arg("spec"), pyb::arg("threads"), pyb::arg("simd"), pyb::arg("opencl_device"),
             pyb::arg("vulkan_device"), pyb::arg("opencl_work_group"), pyb::arg("vulkan_work_group"), pyb::arg("opencl_cache_dir"),
             pyb::arg("vulkan_cache_dir"), pyb::arg("particles_per_group"), pyb::arg("quad_maps"), pyb::arg("subgroups"),
             pyb::arg("force_staging"), pyb::arg("validation"))
        .def_property_readonly("name", [](const PyBackend& b) { return b.name; })
        .def_property_readonly("info", [](PyBackend& b) {
            std::lock_guard lock(b.mutex);
            return device_dict(b.open_backend().info());
        })
        .def_property_readonly("closed", [](PyBackend& b) {
            std::lock_guard lock(b.mutex);
            return !b.impl;
        })
        .def("_upload_map", &upload_map, pyb::arg("map"), pyb::arg("valid"), pyb::arg("times"))
        .def("_score", &score, pyb::arg("map"), pyb::arg("template"), pyb::arg("poses"), pyb::arg("sampling"),
             pyb::arg("min_valid_fraction"), pyb::arg("out"), pyb::arg("times"))
        .def("_sobel", &sobel, pyb::arg("image"), pyb::arg("times"))
        .def("_close", &close);
}

}  // namespace trn::py
