// Localization from Python: trnkit.Localizer (the online DPC-PFL localizer, trn::localize), the
// rows of a recorded AIR folder as a robot would feed them (trnkit.read_air_folder), and a whole
// flight at once (trnkit.localize). Filter work runs with the GIL released.
#include "py_localize.hpp"

#include <pybind11/numpy.h>
#include <pybind11/stl.h>

#include <cmath>
#include <memory>
#include <mutex>
#include <optional>
#include <sstream>
#include <string>
#include <utility>

#include "py_arrays.hpp"
#include "py_backend.hpp"
#include "trn/error.hpp"
#include "trn/field_error.hpp"
#include "trn/io/image_io.hpp"
#include "trn/io/map_pixels.hpp"
#include "trn/localize/air_frames.hpp"
#include "trn/localize/air_inputs.hpp"
#include "trn/localize/localization.hpp"
#include "trn/localize/localizer.hpp"
#include "trn/localize/localizer_defaults.hpp"
#include "trn/localize/report.hpp"
#include "trn/localize/report_folder.hpp"
#include "trn/localize/localizer_settings.hpp"

namespace trn::py {
namespace {

// A library field named as this module's keyword (start_x, start_y are one keyword here).
std::string keyword_of(const std::string& field) {
    if (field == "start_x, start_y") return "start";
    if (field == "flight.folder") return "dataset";
    if (field == "hfov_deg (or focal_px with focal_width)") return "hfov_deg";
    return field;
}

// FieldError as a ValueError naming the keyword.
template <typename Body>
auto naming_keywords(Body&& body) {
    try {
        return body();
    } catch (const FieldError& e) {
        std::string detail = e.detail();
        for (std::size_t at = detail.find('`'); at != std::string::npos; at = detail.find('`', at)) detail.erase(at, 1);
        throw pyb::value_error(keyword_of(e.field()) + ": " + detail);
    }
}

// trnkit.Error (docs/EMBEDDING.md) of a call on a closed Localizer.
constexpr const char* kClosed = "Localizer: closed (or its backend was closed); make a new one";

// Uses its backend under the backend's mutex; the backend's close() releases it (its map on the device).
struct PyLocalizer : BackendUser {
    std::shared_ptr<PyBackend> backend;        // declared first: released after the localizer
    std::unique_ptr<localize::Localizer> impl;  // guarded by backend->mutex; null once closed
    void release_device() override { impl.reset(); }
};

localize::LocalizerConfig make_config(std::optional<std::pair<double, double>> start, std::optional<double> start_heading_rad,
                                      std::optional<double> camera_hfov_deg, double max_tilt_deg, int template_width, double sparse,
                                      std::uint64_t seed, const std::string& conversion, const std::string& sampling,
                                      std::optional<std::size_t> min_particles, std::optional<std::size_t> max_particles,
                                      std::optional<std::size_t> particles, std::optional<double> init_radius_m,
                                      std::optional<double> reinit_radius_m, const std::string& heading, std::optional<double> start_heading_sd_deg,
                                      const std::string& profile, std::optional<bool> lock_monitor,
                                      std::optional<std::pair<double, double>> map_origin,
                                      std::optional<std::size_t> compassless_max_particles = std::nullopt,
                                      bool visual_odometry = localize::kDefaultVisualOdometry) {
    // The profile first (ours or dissertation: docs/PROFILES.md); a keyword given (not None) over it.
    localize::LocalizerConfig c;
    try {
        c = localize::localizer_profile(filter::parse_profile(profile));
    } catch (const Error& e) {
        throw pyb::value_error(std::string("profile: ") + e.what());
    }
    if (lock_monitor) c.filter.lock.enabled = *lock_monitor;
    try {
        c.filter.heading = filter::parse_heading_mode(heading);
    } catch (const Error& e) {
        throw pyb::value_error(std::string("heading: ") + e.what());
    }
    if (start_heading_sd_deg) c.filter.init_heading_sd_deg = *start_heading_sd_deg;
    // Without a compass the prior's spread not given: the library's (compassless_yaw_sd_deg), under
    // either profile, as `trnkit localize --heading none --start-yaw-deg` takes it.
    else if (c.filter.heading == filter::HeadingMode::None) c.filter.init_heading_sd_deg = NAN;
    if (start) c.start_x = start->first, c.start_y = start->second;
    if (start_heading_rad) c.start_heading_rad = *start_heading_rad;
    if (camera_hfov_deg) c.camera_hfov_deg = *camera_hfov_deg;
    c.max_tilt_deg = max_tilt_deg;
    if (template_width < 0) throw pyb::value_error("template_width: must be >= 0 (0: the frame's full width)");
    c.scoring.template_width = template_width;
    if (!(sparse > 0 && sparse <= 1)) throw pyb::value_error("sparse: the share of template pixels scored must be in (0, 1]");
    if (sparse < 1) c.scoring.sampling = Sampling::random(sparse, seed);
    c.filter.seed = seed;
    try {
        c.filter.conversion = filter::Conversion::parse(conversion);
    } catch (const Error& e) {
        throw pyb::value_error(std::string("conversion: ") + e.what());
    }
    try {
        c.filter.sampling = filter::parse_sampling_method(sampling);
    } catch (const Error& e) {
        throw pyb::value_error(std::string("sampling: ") + e.what());
    }
    if (min_particles) c.filter.min_particles = *min_particles;
    if (max_particles) c.filter.max_particles = *max_particles, c.compassless_max_particles = 0;  // the count given is the count
    if (compassless_max_particles) c.compassless_max_particles = *compassless_max_particles;
    if (particles) c.filter.fixed_particles = *particles;
    if (init_radius_m) c.filter.init_radius_m = *init_radius_m;
    if (reinit_radius_m) c.filter.reinit_radius_m = *reinit_radius_m;
    if (map_origin) c.map_origin = sim::GeoOrigin{map_origin->first, map_origin->second};
    c.visual_odometry = visual_odometry;
    return c;
}

// Optional value or None.
pyb::object maybe(double v) { return std::isfinite(v) ? pyb::object(pyb::float_(v)) : pyb::object(pyb::none()); }

pyb::dict estimate_dict(const localize::Estimate& e) {
    pyb::dict d;
    d["x"] = e.x, d["y"] = e.y, d["yaw"] = e.yaw;
    d["best_x"] = e.best_x, d["best_y"] = e.best_y, d["best_yaw"] = e.best_yaw, d["best_ncc"] = e.best_ncc;
    d["spread_m"] = e.spread_m;
    d["particles"] = e.particles, d["off_map"] = e.off_map;
    d["frame_missing"] = e.frame_missing, d["too_oblique"] = e.too_oblique, d["tilt_deg"] = e.tilt_deg;
    d["odometry_lost"] = e.odometry_lost, d["reinitialised"] = e.reinitialised;
    d["lock_state"] = localize::lock_state_name(e.lock);
    d["odometry_source"] = e.odometry_source;
    d["lock_contrast"] = e.lock.contrast, d["lock_drift_m"] = e.lock.drift_m;
    d["score_ms"] = e.score_ms, d["step_ms"] = e.step_ms;
    d["yaw_sd"] = e.yaw_sd;
    d["cov_xx_px2"] = e.cov_xx_px2, d["cov_xy_px2"] = e.cov_xy_px2, d["cov_yy_px2"] = e.cov_yy_px2;
    d["cov_nn_m2"] = e.cov_nn_m2, d["cov_ne_m2"] = e.cov_ne_m2, d["cov_ee_m2"] = e.cov_ee_m2, d["eph_m"] = e.eph_m;
    d["latitude_deg"] = maybe(e.latitude_deg), d["longitude_deg"] = maybe(e.longitude_deg), d["time_s"] = maybe(e.time_s);
    d["vel_north_mps"] = maybe(e.vel_north_mps), d["vel_east_mps"] = maybe(e.vel_east_mps), d["vel_var_m2ps2"] = maybe(e.vel_var_m2ps2);
    return d;
}

pyb::dict step(PyLocalizer& l, const pyb::object& frame, std::optional<std::pair<double, double>> odometry,
               std::optional<double> heading_rad, std::optional<double> altitude_agl_m, std::optional<double> scale,
               std::optional<std::pair<double, double>> attitude, std::optional<double> odometry_yaw_rad, std::optional<double> time_s) {
    localize::Observation o;
    if (time_s) o.time_s = *time_s;
    if (odometry_yaw_rad) o.odometry_yaw_rad = *odometry_yaw_rad;
    BorrowedGray image;
    if (!frame.is_none()) {
        image = gray_view(frame, "frame");
        o.frame = image.view;
    }
    if (odometry) o.odometry_east_m = odometry->first, o.odometry_north_m = odometry->second;
    if (heading_rad) o.heading_rad = *heading_rad;
    if (altitude_agl_m) o.altitude_agl_m = *altitude_agl_m;
    if (scale) o.map_px_per_camera_px = *scale;
    if (attitude) o.has_attitude = true, o.roll_rad = attitude->first, o.pitch_rad = attitude->second;
    if (!o.frame.empty() && !scale && !altitude_agl_m)
        throw pyb::value_error("step: give altitude_agl_m (metres above the ground) or scale (map pixels per frame pixel) with a frame");
    localize::Estimate e;
    {
        pyb::gil_scoped_release release;
        std::lock_guard<std::mutex> lock(l.backend->mutex);
        if (!l.impl) throw Error(kClosed);
        e = l.impl->step(o);
    }
    return estimate_dict(e);
}

pyb::dict air_row(const localize::AirFrame& f) {
    pyb::dict d;
    d["row"] = f.row;
    d["filename"] = f.filename;
    d["image_error"] = f.image_error;
    pyb::dict step;  // Localizer.step's keyword arguments
    step["frame"] = f.image.pixels.empty() ? pyb::object(pyb::none()) : pyb::object(gray_array(f.image.view()));
    step["altitude_agl_m"] = f.altitude_agl_m;
    step["heading_rad"] = maybe(f.heading_rad);
    step["attitude"] = pyb::make_tuple(f.roll_rad, f.pitch_rad);
    step["odometry"] = std::isfinite(f.odometry_step.east_m) ? pyb::object(pyb::make_tuple(f.odometry_step.east_m, f.odometry_step.north_m))
                                                             : pyb::object(pyb::none());
    d["step"] = step;
    pyb::dict nc;  // the same for heading="none": no heading, odometry in the previous frame's axes, its rotation
    for (auto item : step) nc[item.first] = item.second;
    nc["heading_rad"] = pyb::none();
    nc["odometry"] = std::isfinite(f.compassless_step.forward_m)
                         ? pyb::object(pyb::make_tuple(f.compassless_step.right_m, f.compassless_step.forward_m))
                         : pyb::object(pyb::none());
    nc["odometry_yaw_rad"] = maybe(f.compassless_step.rotation_rad);
    d["step_without_compass"] = nc;
    d["truth"] = std::isfinite(f.truth_x) ? pyb::object(pyb::make_tuple(f.truth_x, f.truth_y)) : pyb::object(pyb::none());
    return d;
}

pyb::list read_air_folder(const std::string& folder) {
    return naming_keywords([&] {
        localize::AirFrameReader reader(folder);
        localize::AirFrame f;
        pyb::list rows;
        while (reader.next(f)) rows.append(air_row(f));
        return rows;
    });
}

// The rows as NumPy columns.
pyb::dict columns(const std::vector<localize::LocalizationRow>& rows) {
    const auto n = static_cast<pyb::ssize_t>(rows.size());
    auto column = [&](auto get) {
        pyb::array_t<double> a(n);
        for (pyb::ssize_t i = 0; i < n; ++i) a.mutable_at(i) = get(rows[i]);
        return a;
    };
    using Row = localize::LocalizationRow;
    pyb::dict d;
    d["frame"] = column([](const Row& r) { return static_cast<double>(r.frame); });
    d["time_s"] = column([](const Row& r) { return r.time_s; });
    d["distance_m"] = column([](const Row& r) { return r.distance_m; });
    d["truth_x"] = column([](const Row& r) { return r.truth_x; });
    d["truth_y"] = column([](const Row& r) { return r.truth_y; });
    d["odometry_x"] = column([](const Row& r) { return r.odometry_x; });
    d["odometry_y"] = column([](const Row& r) { return r.odometry_y; });
    d["estimate_x"] = column([](const Row& r) { return r.estimate_x; });
    d["estimate_y"] = column([](const Row& r) { return r.estimate_y; });
    d["estimate_yaw"] = column([](const Row& r) { return r.estimate_yaw; });
    d["estimate_yaw_sd"] = column([](const Row& r) { return r.estimate_yaw_sd; });
    d["truth_yaw"] = column([](const Row& r) { return r.truth_yaw; });
    d["error_m"] = column([](const Row& r) { return r.error_m; });
    d["odometry_error_m"] = column([](const Row& r) { return r.odometry_error_m; });
    d["particles"] = column([](const Row& r) { return static_cast<double>(r.particles); });
    d["score_ms"] = column([](const Row& r) { return r.score_ms; });
    d["estimate_lat"] = column([](const Row& r) { return r.estimate_lat; });
    d["estimate_lon"] = column([](const Row& r) { return r.estimate_lon; });
    d["cov_nn_m2"] = column([](const Row& r) { return r.cov_nn_m2; });
    d["cov_ne_m2"] = column([](const Row& r) { return r.cov_ne_m2; });
    d["cov_ee_m2"] = column([](const Row& r) { return r.cov_ee_m2; });
    d["error_sigmas"] = column([](const Row& r) { return r.error_sigmas; });
    return d;
}

pyb::dict summary_dict(const localize::LocalizationSummary& s) {
    pyb::dict d;
    d["steps"] = s.steps;
    d["filter_mean_error_m"] = maybe(s.filter_mean_error_m), d["odometry_mean_error_m"] = maybe(s.odometry_mean_error_m);
    d["filter_final_error_m"] = maybe(s.filter_final_error_m), d["odometry_final_error_m"] = maybe(s.odometry_final_error_m);
    d["filter_error_slope_m_per_km"] = maybe(s.filter_error_slope_m_per_km);
    d["odometry_error_slope_m_per_km"] = maybe(s.odometry_error_slope_m_per_km);
    d["distance_m"] = s.distance_m, d["mean_particles"] = s.mean_particles;
    d["frames_per_second"] = s.frames_per_second, d["mean_score_ms"] = s.mean_score_ms;
    d["frames_too_oblique"] = s.frames_too_oblique;
    d["odometry_lost"] = s.counters.odometry_lost, d["frames_missing"] = s.counters.frames_missing;
    d["reinitialisations"] = s.counters.reinitialisations, d["lock_lost_events"] = s.counters.lock_lost_events;
    d["truth_inside_1sigma"] = maybe(s.inside_1sigma), d["truth_inside_2sigma"] = maybe(s.inside_2sigma);
    return d;
}

pyb::dict localize_flight(const std::string& dataset, const std::string& map, const std::shared_ptr<PyBackend>& backend, double metres_per_pixel,
                          double hfov_deg, double fps, double rate_hz, std::optional<std::pair<double, double>> start,
                          std::optional<double> start_heading_rad, const std::string& odometry, double max_tilt_deg, int template_width,
                          double sparse, std::uint64_t seed, const std::string& conversion, const std::string& sampling,
                          std::optional<std::size_t> min_particles, std::optional<std::size_t> max_particles,
                          std::optional<std::size_t> particles, std::optional<double> init_radius_m, std::optional<double> reinit_radius_m,
                          const std::string& out, bool plots, const std::string& heading, std::optional<double> start_heading_sd_deg, int nodata,
                          const std::string& profile, std::optional<bool> lock_monitor,
                          std::optional<std::size_t> compassless_max_particles) {
    if (odometry != "recorded" && odometry != "visual") throw pyb::value_error("odometry: 'recorded' (the folder's SvoX/SvoY) or 'visual', got '" + odometry + "'");
    return naming_keywords([&] {
        localize::AirInputOptions io;
        io.dataset = dataset, io.map = map, io.metres_per_pixel = metres_per_pixel, io.hfov_deg = hfov_deg, io.fps = fps, io.nodata = nodata;
        const localize::AirInputs in = localize::resolve_air_inputs(io);
        localize::LocalizationSpec spec;
        spec.flight = localize::AirFolderFlight{dataset, in.camera, in.fps, max_tilt_deg, in.has_flight_json};
        spec.odometry = odometry == "visual" ? localize::OdometryKind::Visual : localize::OdometryKind::Recorded;
        spec.rate_hz = rate_hz;
        spec.to_latlon = in.to_latlon;
        spec.localizer = make_config(start, start_heading_rad, std::nullopt, max_tilt_deg, template_width, sparse, seed, conversion, sampling,
                                     min_particles, max_particles, particles, init_radius_m, reinit_radius_m, heading, start_heading_sd_deg, profile,
                                     lock_monitor, std::nullopt, compassless_max_particles);
        if (!backend) throw pyb::type_error("backend: a trnkit.Backend");
        localize::LocalizationResult r;
        {
            pyb::gil_scoped_release release;
            std::lock_guard<std::mutex> lock(backend->mutex);  // the whole flight on this backend
            r = localize::run_localization(spec, in.map, backend->open_backend());
            if (!out.empty()) {
                localize::ReportOptions report;
                report.owner = "localize", report.folder_name = "out", report.plots = plots, report.plot_title = in.scenario;
                report.odometry = odometry == "visual" ? "visual" : "folder";
                report.strings = {{"dataset", dataset}, {"map", in.map_path}};
                std::ostringstream ignored;
                localize::write_localization_report(r, out, in.map.image.view(), in.map.metres_per_pixel, report, ignored);
            }
        }
        pyb::dict d;
        d["rows"] = columns(r.rows);
        d["summary"] = summary_dict(r.summary);
        if (r.run.heading == "none")
            for (const auto& [k, v] : localize::heading_numbers(r.summary)) d["summary"][pyb::str(k)] = maybe(v);
        d["backend"] = r.run.backend;
        d["metres_per_pixel"] = in.map.metres_per_pixel;
        d["start"] = pyb::make_tuple(r.run.start_x, r.run.start_y);
        return d;
    });
}

}  // namespace

void register_localize(pyb::module_& m) {
    using namespace pyb::literals;
    pyb::class_<PyLocalizer, std::shared_ptr<PyLocalizer>>(m, "_Localizer", R"(The online DPC-PFL localizer (trn::localize::Localizer).

Built once from the map (a 2-D uint8 array, grey), its resolution and a backend; stepped once per
camera frame. Conventions: map pixels (x east, y south, pixel centres at integers); yaw and
headings in RADIANS, clockwise from north; odometry in metres east/north since the previous step.
Same inputs, same seed: the same estimates as `trnkit localize`, bit for bit.)")
        .def(pyb::init([](const pyb::object& map, double metres_per_pixel, std::shared_ptr<PyBackend> backend, const pyb::object& valid,
                          std::pair<double, double> start,
                          std::optional<double> start_heading_rad, std::optional<double> camera_hfov_deg, double max_tilt_deg,
                          int template_width, double sparse, std::uint64_t seed, const std::string& conversion, const std::string& sampling,
                          std::optional<std::size_t> min_particles, std::optional<std::size_t> max_particles,
                          std::optional<std::size_t> particles, std::optional<double> init_radius_m, std::optional<double> reinit_radius_m,
                          const std::string& heading, std::optional<double> start_heading_sd_deg, const std::string& profile,
                          std::optional<bool> lock_monitor, std::optional<std::pair<double, double>> map_origin,
                          std::optional<std::size_t> compassless_max_particles, bool visual_odometry) {
                 auto l = std::make_shared<PyLocalizer>();
                 const localize::LocalizerConfig c =
                     make_config(start, start_heading_rad, camera_hfov_deg, max_tilt_deg, template_width, sparse, seed, conversion, sampling,
                                 min_particles, max_particles, particles, init_radius_m, reinit_radius_m, heading, start_heading_sd_deg, profile,
                                 lock_monitor, map_origin, compassless_max_particles, visual_odometry);
                 const BorrowedGray view = gray_view(map, "map");
                 const std::optional<BorrowedGray> mask =
                     valid.is_none() ? std::nullopt : std::optional<BorrowedGray>(gray_view(valid, "valid"));
                 if (!backend) throw pyb::type_error("backend: a trnkit.Backend");
                 l->backend = backend;
                 pyb::gil_scoped_release release;  // the map upload
                 std::lock_guard<std::mutex> lock(backend->mutex);
                 Backend& b = backend->open_backend();
                 naming_keywords([&] {
                     l->impl = std::make_unique<localize::Localizer>(view.view, metres_per_pixel, b, c, mask ? mask->view : GrayView{});
                     return 0;
                 });
                 std::erase_if(backend->users, [](const std::weak_ptr<BackendUser>& u) { return u.expired(); });
                 backend->users.push_back(l);
                 return l;
             }),
             "map"_a, "metres_per_pixel"_a, "backend"_a, pyb::kw_only(), "valid"_a = pyb::none(), "start"_a, "start_heading_rad"_a = pyb::none(),
             "camera_hfov_deg"_a = pyb::none(), "max_tilt_deg"_a = 10.0, "template_width"_a = 160, "sparse"_a = 1.0, "seed"_a = 1,
             "conversion"_a = "logistic:0.2", "sampling"_a = "kld", "min_particles"_a = pyb::none(), "max_particles"_a = pyb::none(),
             "particles"_a = pyb::none(), "init_radius_m"_a = pyb::none(), "reinit_radius_m"_a = pyb::none(), "heading"_a = "compass",
             "start_heading_sd_deg"_a = pyb::none(), "profile"_a = "ours", "lock_monitor"_a = pyb::none(),
             "map_origin"_a = pyb::none(), "compassless_max_particles"_a = pyb::none(),
             "visual_odometry"_a = localize::kDefaultVisualOdometry,
             R"(map: 2-D uint8 array; metres_per_pixel: its resolution; backend: a trnkit.Backend (python/trnkit/_localize.py
also takes a spec string and then owns the backend).
start: (x, y) map pixels, the last known position. start_heading_rad: centre of the initial headings
(None: the first step's heading). camera_hfov_deg: horizontal field of view, needed when steps give
altitude_agl_m or attitude. heading: "compass" (each step's heading_rad sets the yaw) or "none"
(no compass: yaw estimated, start_heading_rad None = uniform prior, else Gaussian with
start_heading_sd_deg degrees; steps give odometry in the previous frame's axes (right_m, forward_m)
and odometry_yaw_rad). map_origin: (latitude, longitude) of map pixel (0, 0) on a north-up map
(estimates then also in degrees), or None. visual_odometry: a step without odometry takes it from its
frame against the previous one (as `trnkit localize --odometry visual`); odometry given wins.
The rest are the filter's settings (trn/filter/particle_filter.hpp).)")
        .def("step", &step, "frame"_a = pyb::none(), pyb::kw_only(), "odometry"_a = pyb::none(), "heading_rad"_a = pyb::none(),
             "altitude_agl_m"_a = pyb::none(), "scale"_a = pyb::none(), "attitude"_a = pyb::none(), "odometry_yaw_rad"_a = pyb::none(),
             "time_s"_a = pyb::none(),
             R"(One camera frame (2-D uint8, grey, as taken; None: no frame this step) and the sensors since the last step:
odometry (east_m, north_m) displacement or None (lost); heading_rad compass heading or None;
altitude_agl_m metres above the ground, or scale (map pixels per frame pixel); attitude (roll_rad,
pitch_rad) or None (a tilted frame is warped to nadir, beyond max_tilt_deg not scored);
odometry_yaw_rad (heading="none"): the frame's rotation since the last step, clockwise, or None.
time_s: when the frame was taken, seconds on one clock (velocity needs two steps with it), or None.
Returns a dict: x, y, yaw (radians), best_*, spread_m, particles, off_map, frame_missing,
too_oblique, tilt_deg, odometry_lost, reinitialised, odometry_source ("given", "none", "visual:..."),
lock_state, lock_contrast, lock_drift_m,
score_ms, step_ms, yaw_sd (circular sd of the yaws, radians), the covariance cov_xx_px2, cov_xy_px2,
cov_yy_px2 (map) and cov_nn_m2, cov_ne_m2, cov_ee_m2 (north/east), eph_m, latitude_deg, longitude_deg,
time_s, vel_north_mps, vel_east_mps, vel_var_m2ps2 (None when unknown).)")
        .def(
            "reanchor",
            [](PyLocalizer& l, std::pair<double, double> position, double radius_m, std::optional<double> heading_rad) {
                pyb::gil_scoped_release release;
                std::lock_guard<std::mutex> lock(l.backend->mutex);
                if (!l.impl) throw Error(kClosed);
                l.impl->reanchor(position.first, position.second, radius_m, heading_rad ? *heading_rad : NAN);
            },
            "position"_a, pyb::kw_only(), "radius_m"_a, "heading_rad"_a = pyb::none(),
            "Re-anchors the filter on position (x, y) map pixels within radius_m metres (trn::localize::Localizer::reanchor).")
        .def(
            "close",
            [](PyLocalizer& l) {
                pyb::gil_scoped_release release;
                std::lock_guard<std::mutex> lock(l.backend->mutex);
                l.impl.reset();
            },
            "Releases the map on the device now (the backend stays open).");

    m.def(
        "_localizer_settings",
        [](std::optional<double> start_heading_rad, std::optional<double> camera_hfov_deg, double max_tilt_deg, int template_width,
           double sparse, std::uint64_t seed, const std::string& conversion, const std::string& sampling,
           std::optional<std::size_t> min_particles, std::optional<std::size_t> max_particles, std::optional<std::size_t> particles,
           std::optional<double> init_radius_m, std::optional<double> reinit_radius_m, const std::string& heading,
           std::optional<double> start_heading_sd_deg, const std::string& profile, std::optional<bool> lock_monitor,
           std::optional<std::size_t> compassless_max_particles, bool visual_odometry) {
            return localize::settings_json(make_config(std::nullopt, start_heading_rad, camera_hfov_deg, max_tilt_deg, template_width, sparse,
                                                       seed, conversion, sampling, min_particles, max_particles, particles, init_radius_m,
                                                       reinit_radius_m, heading, start_heading_sd_deg, profile, lock_monitor, std::nullopt,
                                                       compassless_max_particles, visual_odometry));
        },
        pyb::kw_only(), "start_heading_rad"_a = pyb::none(), "camera_hfov_deg"_a = pyb::none(), "max_tilt_deg"_a = localize::LocalizerConfig{}.max_tilt_deg,
        "template_width"_a = localize::LocalizerConfig{}.scoring.template_width, "sparse"_a = 1.0, "seed"_a = filter::FilterConfig{}.seed,
        "conversion"_a = filter::FilterConfig{}.conversion.to_string(), "sampling"_a = filter::to_string(filter::FilterConfig{}.sampling),
        "min_particles"_a = pyb::none(), "max_particles"_a = pyb::none(), "particles"_a = pyb::none(), "init_radius_m"_a = pyb::none(),
        "reinit_radius_m"_a = pyb::none(), "heading"_a = "compass", "start_heading_sd_deg"_a = pyb::none(), "profile"_a = "ours",
        "lock_monitor"_a = pyb::none(), "compassless_max_particles"_a = pyb::none(), "visual_odometry"_a = localize::kDefaultVisualOdometry,
        "The LocalizerConfig these keywords make (as trnkit.Localizer makes it) as JSON under docs/EMBEDDING.md's names; with no "
        "keyword: the library's defaults (trn/localize/localizer_defaults.hpp).");
    m.attr("DEFAULT_BACKEND") = localize::kDefaultBackend;
    m.attr("DEFAULT_RATE_HZ") = localize::kDefaultRateHz;

    m.def(
        "_load_gray",
        [](const std::string& path) { return gray_array(load_gray(path).view()); },
        "path"_a, "An image file (PNG, JPEG, TIFF ...) as a 2-D uint8 array, grey.");
    m.def(
        "_load_map",
        [](const std::string& path, std::optional<int> nodata) {
            io::MapPixels p = io::load_map_pixels(path, nodata);
            return pyb::make_tuple(gray_array(p.image.view()), p.valid.width == 0 ? pyb::object(pyb::none()) : pyb::object(gray_array(p.valid.view())));
        },
        "path"_a, "nodata"_a, "A map image as `trnkit localize` reads it: (grey 2-D uint8 array, its no-data or None).");
    m.def(
        "_load_validity",
        [](const std::string& path, std::optional<int> nodata) -> pyb::object {
            const GrayImage valid = load_validity(path, nodata);
            if (valid.width == 0) return pyb::none();
            return gray_array(valid.view());
        },
        "path"_a, "nodata"_a, "An image file's no-data as a 2-D uint8 array (255 valid, 0 not), or None when every pixel is valid.");

    m.def("_read_air_folder", &read_air_folder, "folder"_a,
          R"(The rows of an AIR flight folder (metadata.csv + frames) as a robot's sensors would feed a Localizer:
a list of dicts with row, filename, image_error, truth ((x, y) map pixels or None) and step: the
keyword arguments of Localizer.step (frame as taken, odometry since the previous row, heading_rad,
altitude_agl_m, attitude).)");

    m.def("_localize", &localize_flight, pyb::kw_only(), "dataset"_a, "map"_a = "", "backend"_a, "metres_per_pixel"_a = 0.0,
          "hfov_deg"_a = 0.0, "fps"_a = 0.0, "rate_hz"_a = 5.0, "start"_a = pyb::none(), "start_heading_rad"_a = pyb::none(),
          "odometry"_a = "recorded", "max_tilt_deg"_a = 10.0, "template_width"_a = 160, "sparse"_a = 1.0, "seed"_a = 1,
          "conversion"_a = "logistic:0.2", "sampling"_a = "kld", "min_particles"_a = pyb::none(), "max_particles"_a = pyb::none(),
          "particles"_a = pyb::none(), "init_radius_m"_a = pyb::none(), "reinit_radius_m"_a = pyb::none(), "out"_a = "", "plots"_a = false,
          "heading"_a = "compass", "start_heading_sd_deg"_a = pyb::none(), "nodata"_a = -1, "profile"_a = "ours", "lock_monitor"_a = pyb::none(),
          "compassless_max_particles"_a = pyb::none(),
          R"(Localizes a whole AIR folder, as `trnkit localize` does (the same defaults: trn/localize/localizer_defaults.hpp).
map: the map image (default: the one flight.json names); metres_per_pixel, hfov_deg, fps: when
flight.json does not say (0: not given); start: (x, y) map pixels (None: the first row's truth);
odometry: 'recorded' or 'visual'; out: a folder for localization.csv and summary.json ('' none).
Returns {'rows': dict of NumPy columns, 'summary': dict, 'backend', 'metres_per_pixel', 'start'}.)");
}

}  // namespace trn::py
