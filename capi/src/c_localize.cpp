// The localizer, images and AIR folders through the C API (trn::localize).
#include <cmath>
#include <memory>
#include <string>

#include "c_status.hpp"
#include "trn/filter/conversion.hpp"
#include "trn/io/image_io.hpp"
#include "trn/localize/air_frames.hpp"
#include "trn/localize/localizer.hpp"
#include "trn/localize/localizer_defaults.hpp"
#include "trn/trnkit.h"
#include "c_handles.hpp"

using trn::capi::guarded;
using trn::capi::InvalidArgument;
using trn::capi::require_pointer;

struct trn_localizer {
    std::shared_ptr<trn::Backend> backend;  // declared first: the localizer is released before its backend
    std::unique_ptr<trn::localize::Localizer> impl;
};

struct trn_image {
    trn::GrayImage image;
};

struct trn_air_reader {
    trn::localize::AirFrameReader reader;
    trn::localize::AirFrame frame;  // the row last returned (its strings and pixels)
};

namespace {

trn::filter::Profile profile_named(const char* name, const char* what) {
    try {
        return trn::filter::parse_profile(name ? name : "ours");
    } catch (const trn::Error& e) {
        throw InvalidArgument(std::string(what) + ": " + e.what());
    }
}

trn::localize::LocalizerConfig to_config(const trn_localizer_config& c) {
    // The profile first (what the struct has no field for), then every field over it.
    trn::localize::LocalizerConfig l = trn::localize::localizer_profile(profile_named(c.profile, "config->profile"));
    l.start_x = c.start_x, l.start_y = c.start_y, l.start_heading_rad = c.start_heading_rad;
    l.camera_hfov_deg = c.camera_hfov_deg, l.max_tilt_deg = c.max_tilt_deg;
    l.scoring.template_width = c.template_width;
    if (!(c.sparse > 0 && c.sparse <= 1)) throw InvalidArgument("config->sparse must be in (0, 1], got " + std::to_string(c.sparse));
    if (c.sparse < 1) l.scoring.sampling = trn::Sampling::random(c.sparse, c.seed);
    trn::filter::FilterConfig& f = l.filter;
    f.seed = c.seed;
    if (c.conversion) f.conversion = trn::filter::Conversion::parse(c.conversion);
    if (c.sampling) f.sampling = trn::filter::parse_sampling_method(c.sampling);
    f.min_particles = c.min_particles, f.max_particles = c.max_particles, f.fixed_particles = c.particles;
    f.init_radius_m = c.init_radius_m, f.reinit_radius_m = c.reinit_radius_m;
    if (c.heading) {
        try {
            f.heading = trn::filter::parse_heading_mode(c.heading);
        } catch (const trn::Error& e) {
            throw InvalidArgument(std::string("config->heading: ") + e.what());
        }
    }
    f.init_heading_sd_deg = c.start_heading_sd_deg;
    f.lock.enabled = c.lock_monitor != 0;
    if (std::isnan(c.map_origin_lat_deg) != std::isnan(c.map_origin_lon_deg))
        throw InvalidArgument("config->map_origin_lat_deg and map_origin_lon_deg go together (both NaN: no georeference)");
    if (!std::isnan(c.map_origin_lat_deg)) l.map_origin = trn::sim::GeoOrigin{c.map_origin_lat_deg, c.map_origin_lon_deg};
    l.compassless_max_particles = c.compassless_max_particles, l.compassless_yaw_sd_deg = c.compassless_yaw_sd_deg;
    l.visual_odometry = c.visual_odometry != 0;
    return l;
}

trn::localize::Observation from_c(const trn_observation& o) {
    trn::localize::Observation x;
    if (o.frame) {
        if (o.width <= 0 || o.height <= 0 || o.stride < o.width)
            throw InvalidArgument("observation frame " + std::to_string(o.width) + "x" + std::to_string(o.height) + " with stride " +
                                  std::to_string(o.stride) + " is not a valid image");
        x.frame = trn::GrayView{o.frame, o.width, o.height, o.stride};
    }
    x.map_px_per_camera_px = o.map_px_per_camera_px, x.altitude_agl_m = o.altitude_agl_m;
    x.odometry_east_m = o.odometry_east_m, x.odometry_north_m = o.odometry_north_m;
    x.heading_rad = o.heading_rad;
    x.has_attitude = o.has_attitude != 0, x.roll_rad = o.roll_rad, x.pitch_rad = o.pitch_rad;
    x.odometry_yaw_rad = o.odometry_yaw_rad;
    x.time_s = o.time_s;
    return x;
}

trn_observation to_c(const trn::localize::Observation& o) {
    trn_observation c = trn_observation_default();
    if (!o.frame.empty()) c.frame = o.frame.data, c.width = o.frame.width, c.height = o.frame.height, c.stride = o.frame.stride;
    c.map_px_per_camera_px = o.map_px_per_camera_px, c.altitude_agl_m = o.altitude_agl_m;
    c.odometry_east_m = o.odometry_east_m, c.odometry_north_m = o.odometry_north_m;
    c.heading_rad = o.heading_rad;
    c.has_attitude = o.has_attitude, c.roll_rad = o.roll_rad, c.pitch_rad = o.pitch_rad;
    c.odometry_yaw_rad = o.odometry_yaw_rad;
    c.time_s = o.time_s;
    return c;
}

trn_localizer_config config_of(trn::filter::Profile profile) {
    const trn::localize::LocalizerConfig l = trn::localize::localizer_profile(profile);
    trn_localizer_config c{};
    c.start_x = c.start_y = NAN, c.start_heading_rad = NAN;
    c.camera_hfov_deg = NAN, c.max_tilt_deg = l.max_tilt_deg;
    c.template_width = l.scoring.template_width;
    c.sparse = 1;
    c.seed = l.filter.seed;
    c.conversion = nullptr, c.sampling = nullptr;
    c.min_particles = l.filter.min_particles, c.max_particles = l.filter.max_particles, c.particles = l.filter.fixed_particles;
    c.init_radius_m = l.filter.init_radius_m, c.reinit_radius_m = l.filter.reinit_radius_m;
    c.heading = nullptr;
    c.start_heading_sd_deg = l.filter.init_heading_sd_deg;
    c.profile = trn::filter::to_string(profile);  // a static string
    c.lock_monitor = l.filter.lock.enabled ? 1 : 0;
    c.map_origin_lat_deg = c.map_origin_lon_deg = NAN;
    c.compassless_max_particles = l.compassless_max_particles, c.compassless_yaw_sd_deg = l.compassless_yaw_sd_deg;
    c.visual_odometry = l.visual_odometry ? 1 : 0;
    return c;
}

}  // namespace

extern "C" {

trn_localizer_config trn_localizer_config_default(void) { return config_of(trn::filter::Profile::Ours); }

trn_status trn_localizer_config_for_profile(const char* profile, trn_localizer_config* out) {
    return guarded(__func__, [&] {
        require_pointer(out, "out");
        *out = config_of(profile_named(profile, "profile"));
    });
}

trn_observation trn_observation_default(void) {
    trn_observation o{};
    o.frame = nullptr, o.width = o.height = 0, o.stride = 0;
    o.map_px_per_camera_px = o.altitude_agl_m = NAN;
    o.odometry_east_m = o.odometry_north_m = NAN;
    o.heading_rad = NAN;
    o.has_attitude = 0, o.roll_rad = o.pitch_rad = 0;
    o.odometry_yaw_rad = NAN;
    o.time_s = NAN;
    return o;
}

// Both constructors; errors name the function the caller called.
static trn_status create_localizer(const char* function, trn_backend* backend, const uint8_t* map, int width, int height, ptrdiff_t stride,
                                   const uint8_t* valid, ptrdiff_t valid_stride, double metres_per_pixel,
                                   const trn_localizer_config* config, trn_localizer** out) {
    return guarded(function, [&] {
        require_pointer(out, "out");
        *out = nullptr;
        require_pointer(backend, "backend");
        require_pointer(map, "map");
        require_pointer(config, "config");
        if (width <= 0 || height <= 0 || stride < width)
            throw InvalidArgument("map " + std::to_string(width) + "x" + std::to_string(height) + " with stride " + std::to_string(stride) +
                                  " is not a valid image");
        if (valid && valid_stride < width)
            throw InvalidArgument("valid: stride " + std::to_string(valid_stride) + " is smaller than the map width " + std::to_string(width));
        auto l = std::make_unique<trn_localizer>();
        l->backend = backend->impl;
        l->impl = std::make_unique<trn::localize::Localizer>(trn::GrayView{map, width, height, stride}, metres_per_pixel, *l->backend,
                                                             to_config(*config),
                                                             valid ? trn::GrayView{valid, width, height, valid_stride} : trn::GrayView{});
        *out = l.release();
    });
}

trn_status trn_localizer_create(trn_backend* backend, const uint8_t* map, int width, int height, ptrdiff_t stride, double metres_per_pixel,
                                const trn_localizer_config* config, trn_localizer** out) {
    return create_localizer(__func__, backend, map, width, height, stride, nullptr, 0, metres_per_pixel, config, out);
}

trn_status trn_localizer_create_masked(trn_backend* backend, const uint8_t* map, int width, int height, ptrdiff_t stride,
                                       const uint8_t* valid, ptrdiff_t valid_stride, double metres_per_pixel,
                                       const trn_localizer_config* config, trn_localizer** out) {
    return create_localizer(__func__, backend, map, width, height, stride, valid, valid_stride, metres_per_pixel, config, out);
}

trn_status trn_localizer_step(trn_localizer* localizer, const trn_observation* observation, trn_estimate* out) {
    return guarded(__func__, [&] {
        require_pointer(localizer, "localizer");
        require_pointer(observation, "observation");
        require_pointer(out, "out");
        const trn::localize::Estimate e = localizer->impl->step(from_c(*observation));
        trn_estimate c{};
        c.x = e.x, c.y = e.y, c.yaw = e.yaw;
        c.best_x = e.best_x, c.best_y = e.best_y, c.best_yaw = e.best_yaw, c.best_ncc = e.best_ncc;
        c.spread_m = e.spread_m;
        c.particles = e.particles, c.off_map = e.off_map;
        c.frame_missing = e.frame_missing, c.too_oblique = e.too_oblique, c.odometry_lost = e.odometry_lost, c.reinitialised = e.reinitialised;
        c.tilt_deg = e.tilt_deg;
        c.lock_state = trn::localize::lock_state_name(e.lock);
        c.odometry_source = e.odometry_source;
        c.lock_contrast = e.lock.contrast, c.lock_drift_m = e.lock.drift_m;
        c.score_ms = e.score_ms, c.step_ms = e.step_ms;
        c.yaw_sd = e.yaw_sd;
        c.cov_xx_px2 = e.cov_xx_px2, c.cov_xy_px2 = e.cov_xy_px2, c.cov_yy_px2 = e.cov_yy_px2;
        c.cov_nn_m2 = e.cov_nn_m2, c.cov_ne_m2 = e.cov_ne_m2, c.cov_ee_m2 = e.cov_ee_m2, c.eph_m = e.eph_m;
        c.latitude_deg = e.latitude_deg, c.longitude_deg = e.longitude_deg, c.time_s = e.time_s;
        c.vel_north_mps = e.vel_north_mps, c.vel_east_mps = e.vel_east_mps, c.vel_var_m2ps2 = e.vel_var_m2ps2;
        *out = c;
    });
}

trn_status trn_localizer_reanchor(trn_localizer* localizer, double x, double y, double radius_m, double heading_rad) {
    return guarded(__func__, [&] {
        require_pointer(localizer, "localizer");
        try {
            localizer->impl->reanchor(x, y, radius_m, heading_rad);
        } catch (const trn::Error& e) {
            throw InvalidArgument(e.what());
        }
    });
}

void trn_localizer_destroy(trn_localizer* localizer) { delete localizer; }

trn_status trn_image_load(const char* path, trn_image** out) {
    return guarded(__func__, [&] {
        require_pointer(out, "out");
        *out = nullptr;
        require_pointer(path, "path");
        auto image = std::make_unique<trn_image>();
        image->image = trn::load_gray(path);
        *out = image.release();
    });
}

trn_status trn_image_pixels(const trn_image* image, const uint8_t** pixels, int* width, int* height, ptrdiff_t* stride) {
    return guarded(__func__, [&] {
        require_pointer(image, "image");
        const trn::GrayView v = image->image.view();
        if (pixels) *pixels = v.data;
        if (width) *width = v.width;
        if (height) *height = v.height;
        if (stride) *stride = v.stride;
    });
}

void trn_image_destroy(trn_image* image) { delete image; }

trn_status trn_air_reader_open(const char* folder, trn_air_reader** out) {
    return guarded(__func__, [&] {
        require_pointer(out, "out");
        *out = nullptr;
        require_pointer(folder, "folder");
        *out = new trn_air_reader{trn::localize::AirFrameReader(folder), {}};
    });
}

trn_status trn_air_reader_next(trn_air_reader* reader, trn_air_row* out, int* has_row) {
    return guarded(__func__, [&] {
        require_pointer(reader, "reader");
        require_pointer(out, "out");
        require_pointer(has_row, "has_row");
        *has_row = 0;
        if (!reader->reader.next(reader->frame)) return;
        const trn::localize::AirFrame& f = reader->frame;
        trn_air_row r{};
        r.row = f.row;
        r.filename = f.filename.c_str();
        r.image_error = f.image_error.c_str();
        r.observation = to_c(f.observation());
        r.observation_without_compass = to_c(f.observation_without_compass());
        r.truth_x = f.truth_x, r.truth_y = f.truth_y;
        *out = r;
        *has_row = 1;
    });
}

void trn_air_reader_destroy(trn_air_reader* reader) { delete reader; }

}  // extern "C"
