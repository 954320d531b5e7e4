// The reference side of test_capi.c: the C++ API called directly, independently of capi/src.
#include "cxx_reference.h"

#include <cstdio>
#include <exception>
#include <vector>

#include "trn/energy/run_report.hpp"
#include "trn/localize/localizer.hpp"
#include "trn/localize/localizer_defaults.hpp"
#include "trn/registry.hpp"

namespace {

template <typename Body>
int reference(char* error, std::size_t error_size, Body&& body) {
    try {
        body();
        return 0;
    } catch (const std::exception& e) {
        std::snprintf(error, error_size, "%s", e.what());
        return -1;
    }
}

}  // namespace

extern "C" {

int ref_device_names(char* names, size_t size, char* error, size_t error_size) {
    return reference(error, error_size, [&] {
        std::string all;
        for (const auto& family : trn::default_registry().status())
            for (const auto& d : family.devices) all += d.name + "\n";
        std::snprintf(names, size, "%s", all.c_str());
    });
}

int ref_score(const char* spec, const uint8_t* map, int width, int height, ptrdiff_t stride, const trn_template* templ,
              const trn_score_options* options, const trn_pose* poses, size_t count, trn_score* out, char* error, size_t error_size) {
    return reference(error, error_size, [&] {
        auto backend = trn::default_registry().create(spec);
        const trn::MapHandle handle = backend->upload_map({map, width, height, stride});
        trn::TemplateView view = templ->type == TRN_PIXEL_U8
                                     ? trn::TemplateView(trn::GrayView{static_cast<const std::uint8_t*>(templ->data), templ->width,
                                                                       templ->height, templ->stride})
                                     : trn::TemplateView(trn::FloatView{static_cast<const float*>(templ->data), templ->width,
                                                                        templ->height, templ->stride});
        trn::ScoreOptions o;
        o.min_valid_fraction = options->min_valid_fraction;
        if (options->sampling == TRN_SAMPLING_RANDOM) o.sampling = trn::Sampling::random(options->fraction, options->seed);
        if (options->sampling == TRN_SAMPLING_EXPLICIT) {
            std::vector<trn::SamplePoint> pts;
            for (size_t i = 0; i < options->point_count; ++i) pts.push_back({options->points[2 * i], options->points[2 * i + 1]});
            o.sampling = trn::Sampling::explicit_points(pts);
        }
        std::vector<trn::Pose> p;
        for (size_t i = 0; i < count; ++i) p.push_back({poses[i].x, poses[i].y, poses[i].yaw, poses[i].scale});
        std::vector<trn::ParticleScore> s(count);
        backend->score(handle, view, p, o, s);
        for (size_t i = 0; i < count; ++i) out[i] = {s[i].ncc, s[i].cc, s[i].ssd, s[i].valid_samples, s[i].flags};
    });
}

int ref_sobel(const char* spec, const uint8_t* src, int width, int height, ptrdiff_t stride, int16_t* gx, int16_t* gy, char* error,
              size_t error_size) {
    return reference(error, error_size, [&] {
        auto backend = trn::default_registry().create(spec);
        backend->sobel({src, width, height, stride}, {gx, width, height, width}, {gy, width, height, width});
    });
}

int ref_energy(const char* log_path, const char* markers_path, int align_auto, size_t capacity, size_t* count, double* gross_j,
               double* net_j, double* error_j, size_t* samples, int* usable, double* idle_w, double* offset_s, char* error,
               size_t error_size) {
    return reference(error, error_size, [&] {
        trn::energy::IntegrateRequest q;
        q.align = align_auto ? trn::energy::AlignMode::Auto : trn::energy::AlignMode::SameClock;
        const auto r = trn::energy::integrate_files(log_path, "auto", {}, markers_path, q);
        *count = r.frames.size();
        for (size_t i = 0; i < r.frames.size() && i < capacity; ++i) {
            const auto& f = r.frames[i].energy;
            gross_j[i] = f.gross_j, net_j[i] = f.net_j, error_j[i] = f.error_j, samples[i] = f.samples, usable[i] = f.flag.empty();
        }
        *idle_w = r.idle_w;
        *offset_s = r.alignment.mapping.offset_s;
    });
}

int ref_dissertation_localizer(const uint8_t* map, int width, int height, ptrdiff_t stride, double metres_per_pixel, double start_x,
                               double start_y, double init_radius_m, const uint8_t* frame, int frame_width, int frame_height,
                               ptrdiff_t frame_stride, double scale, double heading_rad, int steps, double* x, double* y, size_t* particles,
                               char* error, size_t error_size) {
    return reference(error, error_size, [&] {
        auto backend = trn::default_registry().create("cpu");
        trn::localize::LocalizerConfig c = trn::localize::dissertation_profile();
        c.start_x = start_x, c.start_y = start_y, c.start_heading_rad = heading_rad, c.filter.init_radius_m = init_radius_m;
        trn::localize::Localizer l({map, width, height, stride}, metres_per_pixel, *backend, c);
        trn::localize::Observation o;
        o.frame = {frame, frame_width, frame_height, frame_stride};
        o.map_px_per_camera_px = scale, o.heading_rad = heading_rad, o.odometry_east_m = 1, o.odometry_north_m = 0;
        for (int i = 0; i < steps; ++i) {
            const trn::localize::Estimate e = l.step(o);
            *x = e.x, *y = e.y, *particles = e.particles;
        }
    });
}

}  // extern "C"
