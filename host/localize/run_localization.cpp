#include <algorithm>
#include <cmath>

#include "trn/detail/angles.hpp"
#include "trn/error.hpp"
#include "trn/field_error.hpp"
#include "trn/localize/air_frames.hpp"
#include "trn/localize/localization.hpp"
#include "trn/sim/air_format.hpp"

namespace trn::localize {
namespace {

RunInfo describe(const Localizer& localizer) {
    const LocalizerConfig& c = localizer.config();
    RunInfo info;
    info.backend = localizer.backend_info().name, info.device = localizer.backend_info().device;
    info.conversion = c.filter.conversion.to_string(), info.sampling = filter::to_string(c.filter.sampling);
    info.sparse = c.scoring.sampling.fraction;
    info.seed = c.filter.seed;
    info.template_width = c.scoring.template_width;
    return info;
}

std::size_t stride_for(double fps, double rate_hz) {
    return std::max<std::size_t>(1, static_cast<std::size_t>(std::lround(fps / rate_hz)));
}

}  // namespace

LocalizationResult run_localization(filter::FlightSource& source, Localizer& localizer, const ProgressFn& progress, const StepFn& on_step) {
    if (localizer.started()) throw Error("run_localization: the Localizer has already been started; give it a fresh one");
    LocalizationResult result;
    result.run = describe(localizer);
    result.run.heading = filter::to_string(localizer.config().filter.heading);
    const LocalizerConfig& cfg = localizer.config();
    const double mpp = localizer.metres_per_pixel();
    filter::FlightSample s;
    OdometryIncrements odometry;
    const bool compassless = cfg.filter.heading == filter::HeadingMode::None;
    CompasslessOdometry compassless_odometry;
    double start_x = cfg.start_x, start_y = cfg.start_y;
    double prev_tx = 0, prev_ty = 0, distance_m = 0;
    const std::size_t hint = source.frames_hint();
    double wall_s = 0;
    while (source.next(s)) {
        if (!localizer.started()) {  // the start: the given one, else the first sample's truth ("the last known position")
            if (std::isnan(start_x)) {
                if (!s.has_truth)
                    throw FieldError("start_x, start_y", "required: the flight has no ground truth (MapX/MapY) in its first frame");
                start_x = s.truth_x, start_y = s.truth_y;
            }
            localizer.start(start_x, start_y, std::isnan(cfg.start_heading_rad) && !compassless ? s.heading_rad : cfg.start_heading_rad);
            prev_tx = s.truth_x, prev_ty = s.truth_y;
            result.run.start_x = start_x, result.run.start_y = start_y;
        }
        // The sources give odometry from the start; the Localizer takes it step by step.
        Observation o;
        const OdometryIncrements::Step step = odometry.next(s.odometry_east_m, s.odometry_north_m);
        o.odometry_east_m = step.east_m, o.odometry_north_m = step.north_m;
        o.heading_rad = s.heading_rad;
        if (compassless) {  // the step in the previous frame's axes, the rotation from the odometry's yaw (air_frames.hpp)
            const CompasslessOdometry::Step c = compassless_odometry.next(step, s.odometry_yaw_rad);
            o.heading_rad = NAN;
            o.odometry_east_m = c.right_m, o.odometry_north_m = c.forward_m, o.odometry_yaw_rad = c.rotation_rad;
        }
        if (!s.image.pixels.empty()) o.frame = s.image.view();
        o.map_px_per_camera_px = s.map_px_per_camera_px;  // the source has levelled the frame already
        o.time_s = s.time_s;
        const Estimate e = localizer.step(o);
        wall_s += e.step_ms / 1000;

        LocalizationRow row;
        row.frame = s.frame_index;
        row.time_s = s.time_s;
        if (s.has_truth) {
            distance_m += std::hypot(s.truth_x - prev_tx, s.truth_y - prev_ty) * mpp;
            prev_tx = s.truth_x, prev_ty = s.truth_y;
            row.truth_x = s.truth_x, row.truth_y = s.truth_y;
        }
        row.distance_m = distance_m;
        row.odometry_x = start_x + (odometry.last_east_m() - odometry.origin_east_m()) / mpp;
        row.odometry_y = start_y - (odometry.last_north_m() - odometry.origin_north_m()) / mpp;
        row.estimate_x = e.x, row.estimate_y = e.y, row.estimate_yaw = e.yaw, row.estimate_yaw_sd = e.yaw_sd;
        if (s.has_truth) row.truth_yaw = s.truth_yaw;
        row.best_x = e.best_x, row.best_y = e.best_y;
        if (s.has_truth) {
            row.error_m = std::hypot(row.estimate_x - s.truth_x, row.estimate_y - s.truth_y) * mpp;
            row.odometry_error_m = std::hypot(row.odometry_x - s.truth_x, row.odometry_y - s.truth_y) * mpp;
            row.error_sigmas = error_in_sigmas((row.estimate_x - s.truth_x) * mpp, -(row.estimate_y - s.truth_y) * mpp, e.cov_nn_m2, e.cov_ne_m2, e.cov_ee_m2);
        }
        row.cov_nn_m2 = e.cov_nn_m2, row.cov_ne_m2 = e.cov_ne_m2, row.cov_ee_m2 = e.cov_ee_m2;
        row.particles = e.particles, row.off_map = e.off_map, row.frame_weight = e.frame_weight;
        row.score_ms = e.score_ms, row.step_ms = e.step_ms;
        row.odometry_lost = e.odometry_lost, row.frame_missing = e.frame_missing && !s.too_oblique, row.reinitialised = e.reinitialised;
        row.tilt_deg = s.tilt_deg, row.too_oblique = s.too_oblique;
        row.odometry_source = s.odometry_source;
        row.lock = e.lock;
        result.rows.push_back(row);
        if (on_step) on_step(row, e);
        if (progress) progress(result.rows.size(), hint);
    }
    result.summary = summarise(result.rows, localizer.counters(), wall_s);
    return result;
}

namespace {
LocalizationResult run_on_map(const LocalizationSpec& spec, GrayView map, GrayView valid, double metres_per_pixel, Backend& backend,
                              const RunHooks& hooks) {
    if (!(spec.rate_hz > 0) || !std::isfinite(spec.rate_hz)) throw FieldError("rate_hz", "must be > 0");
    LocalizerConfig cfg = spec.localizer;
    LocalizationResult result;
    RunInfo info;  // what the flight adds to the Localizer's part of the RunInfo: stride, frames, rate
    auto finish = [&](filter::FlightSource& recorded, filter::VisualOdometrySource& visual) {
        if (hooks.started) hooks.started(info);
        // Visual odometry (asked by spec.odometry or cfg.visual_odometry) comes from the source, by the
        // Localizer's own rules (filter::VisualOdometryTrack), so the Localizer takes it as given.
        const bool use_visual = spec.odometry == OdometryKind::Visual || cfg.visual_odometry;
        cfg.visual_odometry = false;
        Localizer localizer(map, metres_per_pixel, backend, cfg, valid);
        StepFn step;  // the row as the result will have it: with latitude / longitude
        if (hooks.step)
            step = [&](const LocalizationRow& r, const Estimate& e) {
                LocalizationRow row = r;
                if (spec.to_latlon) {
                    const sim::LatLon ll = spec.to_latlon(r.estimate_x, r.estimate_y);
                    row.estimate_lat = ll.latitude_deg, row.estimate_lon = ll.longitude_deg;
                }
                hooks.step(row, e);
            };
        result = run_localization(use_visual ? static_cast<filter::FlightSource&>(visual) : recorded, localizer, hooks.progress, step);
        result.run.stride = info.stride, result.run.frames = info.frames, result.run.filter_rate_hz = info.filter_rate_hz;
        result.run.visual_odometry = use_visual;
        if (use_visual) result.run.visual_odometry_counts = visual.counts();
    };
    if (const auto* air = std::get_if<AirFolderFlight>(&spec.flight)) {
        const std::string& folder = air->folder;
        if (folder.empty()) throw FieldError("flight.folder", "required (an AIR flight folder)");
        // Without a frame rate every row is a filter step at rate_hz.
        const double fps = air->fps > 0 ? air->fps : spec.rate_hz;
        info.stride = stride_for(fps, spec.rate_hz);
        info.frames = filter::count_air_rows(folder);
        info.filter_rate_hz = fps / info.stride;
        filter::AirFlightSource source(folder, air->camera, metres_per_pixel, fps, info.stride, (info.frames + info.stride - 1) / info.stride,
                                       {map.width, map.height}, air->max_tilt_deg, air->camera_size_stated);
        {
            sim::AirReader first(folder);
            sim::AirRecord r;
            const bool has_row = first.next(r);
            // The start defaults to the first row's truth: refuse before the run when it has none.
            if (std::isnan(cfg.start_x) && has_row && !std::isfinite(r.map_x))
                throw FieldError("start_x, start_y", "required: " + folder + "/metadata.csv has no ground truth (empty MapX,MapY) in its first row; give `start_x, start_y`" +
                                                         (std::isfinite(r.latitude_deg) ? " (or `start_from_gps`)" : ""));
            // Photos (import-photos) have no recorded odometry: empty SvoX..Z would make every step "lost".
            if (spec.odometry == OdometryKind::Recorded && has_row && std::isnan(r.svo_m.x))
                throw FieldError("odometry", folder + "/metadata.csv has no recorded odometry (empty SvoX..SvoZ, as camera photos have); use visual odometry (computed from the frames)");
        }
        if (hooks.warning)
            for (const std::string& w : source.warnings()) hooks.warning(w);
        cfg.camera_hfov_deg = air->camera.hfov_deg, cfg.max_tilt_deg = air->max_tilt_deg;
        filter::VisualOdometrySource visual(source, metres_per_pixel, {}, cfg.filter.heading == filter::HeadingMode::None);
        try {
            finish(source, visual);
        } catch (const FieldError&) {
            throw;
        } catch (const Error& e) {
            if (std::string(e.what()).rfind(folder, 0) == 0) throw;  // the flight source's own errors name their place
            throw Error(source.position() + ": " + e.what());          // which row of the flight the library choked on
        }
        source.check_unchanged();  // frames of a dataset replaced mid-run are not this flight's: no result
    } else {
        const SimulatedFlight& sim_flight = std::get<SimulatedFlight>(spec.flight);
        if (!sim_flight.world) throw FieldError("flight.world", "required (the scene the simulated camera sees)");
        const double fps = sim_flight.flight.scenario.fps;
        info.stride = stride_for(fps, spec.rate_hz);
        info.filter_rate_hz = fps / info.stride;
        filter::SimulatedFlightSource simulated(*sim_flight.world, sim_flight.flight, info.stride);
        info.frames = simulated.frames_hint() * info.stride;
        cfg.camera_hfov_deg = sim_flight.flight.camera.hfov_deg;
        filter::VisualOdometrySource visual(simulated, sim_flight.world->metres_per_pixel, {}, cfg.filter.heading == filter::HeadingMode::None);
        finish(simulated, visual);
    }
    if (spec.to_latlon)  // the estimates also as latitude / longitude
        for (LocalizationRow& r : result.rows) {
            const sim::LatLon ll = spec.to_latlon(r.estimate_x, r.estimate_y);
            r.estimate_lat = ll.latitude_deg, r.estimate_lon = ll.longitude_deg;
        }
    return result;
}
}  // namespace

LocalizationResult run_localization(const LocalizationSpec& spec, GrayView map, double metres_per_pixel, Backend& backend,
                                    const RunHooks& hooks) {
    return run_on_map(spec, map, GrayView{}, metres_per_pixel, backend, hooks);
}

LocalizationResult run_localization(const LocalizationSpec& spec, const sim::Map& map, Backend& backend, const RunHooks& hooks) {
    return run_on_map(spec, map.image.view(), map.valid_view(), map.metres_per_pixel, backend, hooks);
}

}  // namespace trn::localize
