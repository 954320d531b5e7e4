/* trnkit C API: the accelerated scorer (devices, map upload, plan + score, Sobel) and the energy
 * integration, for C and for anything with a C FFI.
 *
 * Conventions
 *  - Every call that can fail returns a trn_status; TRN_OK is 0. On failure trn_last_error()
 *    returns a message naming the argument, file or device at fault (thread-local, valid until the
 *    thread's next trnkit call). No C++ exception ever crosses this boundary.
 *  - Objects are opaque handles, created by *_create / returned through an out pointer and freed by
 *    the matching *_destroy (NULL is accepted and ignored). A map keeps its backend alive, so maps
 *    and backends may be destroyed in any order.
 *  - A backend is not thread-safe: use one per thread (or lock around it). Plans and results are
 *    read-only after creation and may be shared.
 *  - The geometry, score rules and flags are those of the C++ API (trn/scoring.hpp): a pose is the
 *    map-pixel position of the template centre, the heading in radians and map pixels per template
 *    pixel; invalid particles have flags != 0 and every score 0.
 *  - Strides are in elements (bytes for uint8 images, int16 elements for Sobel outputs).
 */
#ifndef TRN_TRNKIT_H
#define TRN_TRNKIT_H

#include <stddef.h>
#include <stdint.h>

#if defined(_WIN32)
#define TRN_C_API
#else
#define TRN_C_API __attribute__((visibility("default")))
#endif

#ifdef __cplusplus
extern "C" {
#endif

typedef enum trn_status {
    TRN_OK = 0,
    TRN_ERR_INVALID_ARGUMENT = 1, /* a null pointer, a negative or inconsistent size, an unknown enum value */
    TRN_ERR_UNAVAILABLE = 2,      /* the requested backend is not built or has no such device */
    TRN_ERR_FAILED = 3,           /* the library refused the input or the device failed (see trn_last_error) */
    TRN_ERR_OUT_OF_MEMORY = 4,
    TRN_ERR_INTERNAL = 5          /* an unexpected error; please report it with the message */
} trn_status;

/* The message of this thread's last failed call ("" after a successful one). */
TRN_C_API const char* trn_last_error(void);
/* "TRN_OK", "TRN_ERR_INVALID_ARGUMENT", ... */
TRN_C_API const char* trn_status_name(trn_status status);
/* "0.1.0 (commit ...)" */
TRN_C_API const char* trn_version(void);

/* ---- devices ----------------------------------------------------------------------------- */

/* Strings stay valid as long as the list (or backend) they came from. */
typedef struct trn_device_info {
    const char* name;    /* what trn_backend_create takes: "cpu-ref", "cpu", "opencl:0", "vulkan:1" */
    const char* family;  /* "cpu-ref", "cpu", "opencl", "vulkan" */
    const char* device;  /* e.g. "pthread-haswell" */
    const char* type;    /* "cpu", "gpu", "other" */
    const char* driver;
    const char* details;
} trn_device_info;

typedef struct trn_device_list trn_device_list;

/* Every usable device of every backend family this build has (enumerates devices; not cheap). */
TRN_C_API trn_status trn_devices(trn_device_list** out);
TRN_C_API size_t trn_device_count(const trn_device_list* list);
TRN_C_API trn_status trn_device_get(const trn_device_list* list, size_t index, trn_device_info* out);
TRN_C_API void trn_device_list_destroy(trn_device_list* list);

/* ---- backends and maps ------------------------------------------------------------------- */

typedef struct trn_backend trn_backend;
typedef struct trn_map trn_map;

/* spec: "cpu-ref", "cpu", "opencl", "opencl:1", "vulkan:llvmpipe" ... (never a silent fallback). */
TRN_C_API trn_status trn_backend_create(const char* spec, trn_backend** out);
TRN_C_API void trn_backend_destroy(trn_backend* backend);
TRN_C_API trn_status trn_backend_info(const trn_backend* backend, trn_device_info* out);

/* Copies an 8-bit grey map (row stride in bytes, >= width) to the backend. */
TRN_C_API trn_status trn_map_upload(trn_backend* backend, const uint8_t* pixels, int width, int height, ptrdiff_t stride,
                                    trn_map** out);
TRN_C_API void trn_map_destroy(trn_map* map);

/* ---- plan + score ------------------------------------------------------------------------ */

typedef struct trn_pose {
    float x, y, yaw, scale;
} trn_pose;

typedef struct trn_score {
    float ncc, cc, ssd;
    uint32_t valid_samples;
    uint32_t flags; /* 0: valid; else TRN_FLAG_* bits */
} trn_score;

enum {
    TRN_FLAG_TOO_FEW_SAMPLES = 1u << 0,
    TRN_FLAG_FLAT_PATCH = 1u << 1,
    TRN_FLAG_FLAT_TEMPLATE = 1u << 2
};

typedef enum trn_pixel_type { TRN_PIXEL_U8 = 0, TRN_PIXEL_F32 = 1 } trn_pixel_type;

/* A camera template: uint8_t or float pixels, row stride in elements. */
typedef struct trn_template {
    const void* data;
    trn_pixel_type type;
    int width, height;
    ptrdiff_t stride;
} trn_template;

typedef enum trn_sampling_kind { TRN_SAMPLING_DENSE = 0, TRN_SAMPLING_RANDOM = 1, TRN_SAMPLING_EXPLICIT = 2 } trn_sampling_kind;

typedef struct trn_score_options {
    trn_sampling_kind sampling;
    double fraction;          /* RANDOM: share of template pixels, (0, 1] */
    uint64_t seed;            /* RANDOM: same seed -> same pixels on every backend */
    const int32_t* points;    /* EXPLICIT: point_count (u, v) pairs, each inside the template */
    size_t point_count;
    double min_valid_fraction; /* below this share of valid samples a particle is invalid */
} trn_score_options;

/* Dense sampling, min_valid_fraction 0.9 (the C++ defaults). */
TRN_C_API trn_score_options trn_score_options_default(void);

typedef struct trn_plan trn_plan;

/* Validates the template and options and prepares the samples (once per camera frame).
 * options may be NULL for the defaults. The template's pixels are copied. */
TRN_C_API trn_status trn_plan_create(const trn_template* templ, const trn_score_options* options, trn_plan** out);
TRN_C_API size_t trn_plan_sample_count(const trn_plan* plan);
TRN_C_API void trn_plan_destroy(trn_plan* plan);

/* Phase times of one call in milliseconds, from the backend's own clock. */
typedef struct trn_times {
    double upload_ms, execute_ms, download_ms;
} trn_times;

/* Scores count poses; out holds count entries. times may be NULL. */
TRN_C_API trn_status trn_score_poses(trn_backend* backend, const trn_map* map, const trn_plan* plan, const trn_pose* poses,
                                     size_t count, trn_score* out, trn_times* times);

/* ---- Sobel ------------------------------------------------------------------------------- */

/* 3x3 Sobel of a uint8 image into int16 Gx and Gy (each width x height, own strides),
 * reflect-101 borders, bit-exact with OpenCV's cv::Sobel(CV_16S). */
TRN_C_API trn_status trn_sobel(trn_backend* backend, const uint8_t* src, int width, int height, ptrdiff_t src_stride,
                               int16_t* gx, ptrdiff_t gx_stride, int16_t* gy, ptrdiff_t gy_stride);

/* ---- energy integration ------------------------------------------------------------------ */

typedef enum trn_align_mode {
    TRN_ALIGN_SAME_CLOCK = 0, /* the log's times are on the marker clock */
    TRN_ALIGN_OFFSET = 1,     /* log time = marker time + offset_s */
    TRN_ALIGN_AUTO = 2        /* offset and drift estimated from the busy/idle pattern */
} trn_align_mode;

typedef struct trn_energy_options {
    const char* format;              /* power-log format name or "auto" (NULL: "auto"), see docs/ENERGY.md */
    const char* const* parse_options; /* parse_option_count "key=value" parser options */
    size_t parse_option_count;
    trn_align_mode align;
    double offset_s;                 /* OFFSET; AUTO: centre of the search */
    double search_s;                 /* AUTO: half-width of the search, 0: everywhere */
    int insist;                      /* AUTO: accept an ambiguous estimate instead of failing */
    int monotonic;                   /* read the markers' CLOCK_MONOTONIC instead of CLOCK_REALTIME */
    int hold;                        /* zero-order hold instead of the trapezoid rule */
    size_t min_samples;              /* frames with fewer samples are flagged */
} trn_energy_options;

/* Auto format, same clock, trapezoid rule, min_samples 3 (the CLI's defaults). */
TRN_C_API trn_energy_options trn_energy_options_default(void);

typedef struct trn_energy_frame {
    int id;
    double start_s, end_s;   /* on the power log's clock */
    double gross_j, net_j;   /* net: above the idle baseline */
    double error_j;          /* bound of the integration error */
    size_t samples;          /* power samples inside the frame */
    const char* flag;        /* "" when usable, else why not (valid as long as the result) */
} trn_energy_frame;

typedef struct trn_energy_summary {
    size_t frame_count, usable_count, warning_count;
    double idle_w;           /* idle baseline (0 when none could be measured) */
    double offset_s, drift;  /* marker clock -> log clock */
} trn_energy_summary;

typedef struct trn_energy_result trn_energy_result;

/* What `trnkit energy integrate LOG --markers MARKERS` computes: per-frame joules. options may be NULL. */
TRN_C_API trn_status trn_energy_integrate(const char* log_path, const char* markers_path, const trn_energy_options* options,
                                          trn_energy_result** out);
TRN_C_API trn_status trn_energy_summary_get(const trn_energy_result* result, trn_energy_summary* out);
TRN_C_API trn_status trn_energy_frame_get(const trn_energy_result* result, size_t index, trn_energy_frame* out);
/* Warning index (valid as long as the result), or NULL when out of range. */
TRN_C_API const char* trn_energy_warning(const trn_energy_result* result, size_t index);
TRN_C_API void trn_energy_result_destroy(trn_energy_result* result);

#ifdef __cplusplus
}
#endif

#endif /* TRN_TRNKIT_H */
