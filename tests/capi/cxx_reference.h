/* The same operations done with the C++ API directly (cxx_reference.cpp), so test_capi.c can check
 * that the C API returns what C++ callers get. Each returns 0, or -1 with the message in `error`. */
#ifndef TRN_TEST_CXX_REFERENCE_H
#define TRN_TEST_CXX_REFERENCE_H

#include <stddef.h>
#include <stdint.h>

#include "trn/trnkit.h"

#ifdef __cplusplus
extern "C" {
#endif

/* Device names of the default registry, each followed by '\n'. */
int ref_device_names(char* names, size_t size, char* error, size_t error_size);

/* Scores poses on a fresh backend `spec` (map and template as in the C API). */
int ref_score(const char* spec, const uint8_t* map, int width, int height, ptrdiff_t stride, const trn_template* templ,
              const trn_score_options* options, const trn_pose* poses, size_t count, trn_score* out, char* error, size_t error_size);

/* Sobel on a fresh backend into packed width x height outputs. */
int ref_sobel(const char* spec, const uint8_t* src, int width, int height, ptrdiff_t stride, int16_t* gx, int16_t* gy, char* error,
              size_t error_size);

/* trn::energy::integrate_files with the CLI's defaults, aligned on the same clock or automatically;
 * up to `capacity` frames into the arrays, their number into *count. */
int ref_energy(const char* log_path, const char* markers_path, int align_auto, size_t capacity, size_t* count, double* gross_j,
               double* net_j, double* error_j, size_t* samples, int* usable, double* idle_w, double* offset_s, char* error,
               size_t error_size);

/* Steps trn::localize::Localizer, built with localize::dissertation_profile() and the start and
 * radius given, `steps` times on the same frame (scale in map pixels per frame pixel, heading in
 * radians, odometry 1 m east a step); the last estimate's x, y and particle count. */
int ref_dissertation_localizer(const uint8_t* map, int width, int height, ptrdiff_t stride, double metres_per_pixel, double start_x,
                               double start_y, double init_radius_m, const uint8_t* frame, int frame_width, int frame_height,
                               ptrdiff_t frame_stride, double scale, double heading_rad, int steps, double* x, double* y, size_t* particles,
                               char* error, size_t error_size);

#ifdef __cplusplus
}
#endif

#endif
