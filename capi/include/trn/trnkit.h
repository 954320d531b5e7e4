/* trnkit C API: the accelerated scorer (devices, map upload, plan + score, Sobel), the energy
 * integration, the localizer (with AIR-folder reading) and a MAVLink v2 encoder of its estimates,
 * for C and for anything with a C FFI.
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
/* The same with no-data: `valid` (valid_stride bytes per row) is the map's size, non-zero where a
 * pixel is valid; a sample whose 2x2 bilinear cell touches an invalid pixel is left out of every
 * score like one off the map. valid = NULL: every pixel valid (trn_map_upload). */
TRN_C_API trn_status trn_map_upload_masked(trn_backend* backend, const uint8_t* pixels, int width, int height, ptrdiff_t stride,
                                           const uint8_t* valid, ptrdiff_t valid_stride, trn_map** out);
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

/* ---- localization ------------------------------------------------------------------------- */
/* The online DPC-PFL localizer (C++: trn::localize::Localizer): built once from the map, a backend
 * and a config; stepped once per camera frame with what the other sensors said since the previous
 * one. Map pixels (x east, y south, centres at integers), radians clockwise from north. The same
 * inputs give the same estimates as `trnkit localize`, bit for bit. */
typedef struct trn_localizer trn_localizer;
typedef struct trn_localizer_config {
    double start_x, start_y;     /* map pixels: the last known position (required) */
    double start_heading_rad;    /* centre of the initial headings; NaN: the first step's heading */
    double camera_hfov_deg;      /* horizontal field of view, 5 to 170 degrees; needed when steps give altitude or attitude */
    double max_tilt_deg;         /* steps tilted further from nadir are not scored (10) */
    int template_width;          /* frames are downscaled to this width before scoring (160; 0: full) */
    double sparse;               /* share of template pixels scored, (0, 1] (1: dense) */
    uint64_t seed;               /* the filter's random seed (1): same seed, same run */
    const char* conversion;      /* similarity -> probability: "logistic:0.2" (NULL), "linear", "softmax", "rectifying:D" */
    const char* sampling;        /* "kld" (NULL), "importance", "rejection" */
    size_t min_particles, max_particles; /* KLD bounds (100, 2000; the initial set is max_particles) */
    size_t particles;            /* importance / rejection: fixed count (1000) */
    double init_radius_m;        /* initial particles uniform within this radius of the start (ours 50: a GNSS-loss handover; dissertation 300) */
    double reinit_radius_m;      /* re-initialisation radius after a collapse (300) */
    /* "compass" (NULL): each step's heading_rad sets the particles' yaw; "none": no compass, yaw is
     * estimated (start_heading_rad NaN: uniform prior, else Gaussian with start_heading_sd_deg) and
     * turned by observation.odometry_yaw_rad, the odometry then in the previous frame's axes. */
    const char* heading;
    double start_heading_sd_deg; /* spread of the initial headings, degrees (NaN: 2, the motion model's eps_rot; heading "none": compassless_yaw_sd_deg) */
    /* The filter's reading of the dissertation (docs/PROFILES.md): "ours" (NULL) or "dissertation",
     * which also sets what this struct has no field for (KLD quantile, motion model, its noise). Take
     * the defaults from trn_localizer_config_for_profile, then change fields: its values are the
     * profile's, so a field left alone keeps the profile's value. */
    const char* profile;
    int lock_monitor;            /* nonzero: the wrong-lock monitor is on (ours: 1; dissertation: 0) */
    double map_origin_lat_deg, map_origin_lon_deg; /* of map pixel (0, 0), north up: estimates in lat/lon too (NaN: none) */
    /* heading "none" with start_heading_rad NaN (a uniform yaw prior): max_particles is raised to at
     * least this (ours: 6000, the initial set must cover every yaw; 0: off, as the CLI's
     * --max-particles and Python's max_particles given do; dissertation: 0). */
    size_t compassless_max_particles;
    /* heading "none" with a start_heading_rad and start_heading_sd_deg NaN: the yaw prior's sd (10) */
    double compassless_yaw_sd_deg;
    /* nonzero: visual odometry online: a step whose odometry_east_m or odometry_north_m is NaN takes
     * its odometry from its frame against the previous one, as `trnkit localize --odometry visual`
     * (scaled by the previous frame's scale or altitude, turned by the previous heading, or without a
     * compass by its own measured rotations); odometry given is used as given (0: off, the default). */
    int visual_odometry;
} trn_localizer_config;
/* The defaults of the profile "ours": the same as `trnkit localize` and Python's (docs/EMBEDDING.md,
 * "Defaults"); start_x, start_y NaN (to be set). */
TRN_C_API trn_localizer_config trn_localizer_config_default(void);
/* The defaults of a profile ("ours", "dissertation"; NULL: "ours"), with `profile` set to it. An
 * unknown name is TRN_INVALID_ARGUMENT naming both, and *out is left as it was. */
TRN_C_API trn_status trn_localizer_config_for_profile(const char* profile, trn_localizer_config* out);

typedef struct trn_observation {
    const uint8_t* frame;        /* grey camera frame as taken; NULL: no frame this step */
    int width, height;
    ptrdiff_t stride;            /* bytes per row, >= width */
    double map_px_per_camera_px; /* the frame's scale; NaN: from altitude_agl_m and camera_hfov_deg */
    double altitude_agl_m;       /* height above the ground, metres */
    double odometry_east_m, odometry_north_m; /* displacement since the previous step; NaN: lost */
    double heading_rad;          /* compass heading; NaN: none this step */
    int has_attitude;            /* nonzero: roll/pitch measured, a tilted frame is warped to nadir */
    double roll_rad, pitch_rad;
    /* heading "none" only: the frame's rotation since the previous step, clockwise (NaN: unknown);
     * odometry_north_m is then forward (towards the previous frame's top), odometry_east_m to its right. */
    double odometry_yaw_rad;
    double time_s;               /* when the frame was taken, seconds on one clock (NaN: unknown; velocity needs it) */
} trn_observation;
/* No frame, every number NaN, no attitude. */
TRN_C_API trn_observation trn_observation_default(void);

typedef struct trn_estimate {
    double x, y, yaw;             /* weighted mean: map pixels, radians */
    double best_x, best_y, best_yaw, best_ncc; /* the best-scoring particle */
    double spread_m;              /* weighted rms distance of the particles from (x, y) */
    size_t particles, off_map;    /* scored this step / of them without a valid score */
    int frame_missing, too_oblique, odometry_lost, reinitialised;
    double tilt_deg;              /* of the optical axis from the vertical (0 without attitude) */
    const char* lock_state;       /* "none", "unknown", "ok", "weak", "inconsistent", "fix", "lost" (static) */
    double lock_contrast, lock_drift_m; /* the lock monitor's evidence (NaN: not assessed) */
    double score_ms, step_ms;     /* wall time of the scoring / of the whole step */
    double yaw_sd;                /* circular sd of the particles' yaws, radians (the heading's spread) */
    /* The position's covariance (the particles'): map frame (pixels^2, x east, y south) and metres^2
     * north/east; eph_m: 1 sigma on its worst axis. Its calibration on the real flights: RESULTS.md. */
    double cov_xx_px2, cov_xy_px2, cov_yy_px2;
    double cov_nn_m2, cov_ne_m2, cov_ee_m2;
    double eph_m;
    double latitude_deg, longitude_deg; /* of (x, y) with config.map_origin_*; NaN without */
    double time_s;                /* the observation's */
    double vel_north_mps, vel_east_mps, vel_var_m2ps2; /* from this and the previous estimate (NaN: no times) */
    /* the odometry this step used (static): "given", "none", or with config.visual_odometry "visual:start",
     * "visual:features", "visual:phase", "visual:lost", "visual:no-frame" */
    const char* odometry_source;
} trn_estimate;

/* The map (8-bit grey, row stride in bytes) is uploaded to the backend here and need not outlive the
 * call; the localizer keeps its backend alive. */
TRN_C_API trn_status trn_localizer_create(trn_backend* backend, const uint8_t* map, int width, int height, ptrdiff_t stride,
                                          double metres_per_pixel, const trn_localizer_config* config, trn_localizer** out);
/* The same on a map with no-data (`valid` as trn_map_upload_masked takes it; NULL: none). */
TRN_C_API trn_status trn_localizer_create_masked(trn_backend* backend, const uint8_t* map, int width, int height, ptrdiff_t stride,
                                                 const uint8_t* valid, ptrdiff_t valid_stride, double metres_per_pixel,
                                                 const trn_localizer_config* config, trn_localizer** out);
TRN_C_API trn_status trn_localizer_step(trn_localizer* localizer, const trn_observation* observation, trn_estimate* out);
/* Re-anchors the filter on a new position (e.g. a GNSS fix came back): particles uniform within
 * radius_m metres of (x, y) map pixels, the config kept; headings around heading_rad (NaN: without a
 * compass the yaw learnt so far, with one the next step's heading). The lock state reads "unknown"
 * again until the next fix. TRN_INVALID_ARGUMENT off the map or with radius_m not > 0. */
TRN_C_API trn_status trn_localizer_reanchor(trn_localizer* localizer, double x, double y, double radius_m, double heading_rad);
TRN_C_API void trn_localizer_destroy(trn_localizer* localizer);

/* ---- images and recorded flights ---------------------------------------------------------- */
typedef struct trn_image trn_image;
/* Reads an image file (PNG, JPEG, TIFF ...) as 8-bit grey. */
TRN_C_API trn_status trn_image_load(const char* path, trn_image** out);
/* Pixels valid as long as the image. */
TRN_C_API trn_status trn_image_pixels(const trn_image* image, const uint8_t** pixels, int* width, int* height, ptrdiff_t* stride);
TRN_C_API void trn_image_destroy(trn_image* image);

/* An AIR flight folder (metadata.csv + frames) read row by row as a robot's sensors would feed the
 * localizer: trn_air_row.observation is ready for trn_localizer_step (frame as taken, attitude,
 * altitude, compass heading, the odometry since the previous row). */
typedef struct trn_air_reader trn_air_reader;
typedef struct trn_air_row {
    size_t row;                   /* 0-based row of metadata.csv */
    const char* filename;         /* valid until the next call */
    const char* image_error;      /* "" when the frame loaded, else why not (then observation.frame is NULL) */
    trn_observation observation;  /* its frame valid until the next call */
    double truth_x, truth_y;      /* MapX/MapY, map pixels (NaN: none) */
    trn_observation observation_without_compass; /* the same for heading "none": no heading, the odometry in the
                                                    previous frame's axes, odometry_yaw_rad from the heading's change */
} trn_air_row;
TRN_C_API trn_status trn_air_reader_open(const char* folder, trn_air_reader** out);
/* *has_row = 1 and *out filled, or *has_row = 0 at the end. */
TRN_C_API trn_status trn_air_reader_next(trn_air_reader* reader, trn_air_row* out, int* has_row);
TRN_C_API void trn_air_reader_destroy(trn_air_reader* reader);

/* ---- MAVLink v2 out ------------------------------------------------------------------------ */
/* One estimate as MAVLink v2 frames for an autopilot (C++: trn::io::mavlink::Stream, the module
 * `trnkit localize --mavlink` uses; the mapping and the autopilots' parameters: docs/AUTOPILOT.md):
 * a HEARTBEAT when a second of time_us has passed since the last (and first), then GPS_INPUT (232),
 * GLOBAL_POSITION_SENSOR (296) and ODOMETRY (331) as `messages` selects. Send the bytes as one UDP
 * datagram or write them to a serial port. NaN in a field: not known (sent as unknown / ignored). */
typedef struct trn_nav_fix {
    uint64_t time_us;             /* the frame's time: UNIX epoch or since boot, microseconds */
    int valid;                    /* 0: lost / no position: "no fix" is sent */
    int reset;                    /* nonzero: the estimate jumped (ODOMETRY's reset_counter steps) */
    double lat_deg, lon_deg;      /* WGS84 */
    double alt_msl_m;             /* above mean sea level */
    double north_m, east_m;       /* in a fixed local frame (ODOMETRY), metres from its origin */
    double cov_nn, cov_ne, cov_ee; /* horizontal position covariance, m^2 (north, east) */
    double spread_m;              /* rms distance of the estimate's samples: eph when there is no covariance */
    double vel_north, vel_east;   /* m/s */
    double vel_var;               /* m^2/s^2 per axis */
    double yaw_rad, yaw_var;      /* heading clockwise from true north; rad^2 */
    uint32_t processing_us;       /* frame to message, microseconds (GLOBAL_POSITION_SENSOR) */
} trn_nav_fix;
/* time 0, not valid, no reset, every number NaN, processing 0. */
TRN_C_API trn_nav_fix trn_nav_fix_default(void);

#define TRN_MAVLINK_GPS_INPUT 1u       /* GPS_INPUT: ArduPilot's GPS1_TYPE 14 (MAV) */
#define TRN_MAVLINK_GLOBAL_POSITION 2u /* GLOBAL_POSITION_SENSOR: PX4's auxiliary global position */
#define TRN_MAVLINK_ODOMETRY 4u        /* ODOMETRY: external vision (PX4 EKF2_EV_CTRL, ArduPilot VISO_TYPE 1) */
#define TRN_MAVLINK_MAX_BYTES 512      /* a buffer this large always takes one estimate's frames */
typedef struct trn_mavlink_options {
    uint8_t system_id, component_id; /* 1 (the vehicle's), 197 (MAV_COMP_ID_VISUAL_INERTIAL_ODOMETRY) */
    unsigned messages;               /* TRN_MAVLINK_* bits (all three) */
    uint8_t sensor_id;               /* GPS_INPUT gps_id, GLOBAL_POSITION_SENSOR id (0) */
    uint8_t satellites;              /* GPS_INPUT satellites_visible with a fix (10; ArduPilot wants >= 6) */
} trn_mavlink_options;
TRN_C_API trn_mavlink_options trn_mavlink_options_default(void);

typedef struct trn_mavlink_encoder trn_mavlink_encoder;
/* options NULL: the defaults. */
TRN_C_API trn_status trn_mavlink_encoder_create(const trn_mavlink_options* options, trn_mavlink_encoder** out);
/* Writes the frames for `fix` to buffer and their length to *size. A fix out of range (latitude,
 * a negative variance ...) or a buffer too small is TRN_ERR_INVALID_ARGUMENT naming it, and the
 * encoder is left as it was (its sequence number and heartbeat clock). */
TRN_C_API trn_status trn_mavlink_encode(trn_mavlink_encoder* encoder, const trn_nav_fix* fix, uint8_t* buffer, size_t capacity,
                                        size_t* size);
TRN_C_API void trn_mavlink_encoder_destroy(trn_mavlink_encoder* encoder);

#ifdef __cplusplus
}
#endif

#endif /* TRN_TRNKIT_H */
