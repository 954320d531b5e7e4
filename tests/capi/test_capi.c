/* The C API from C: every function against the C++ API on the same inputs (cxx_reference.cpp),
 * against independent oracles where one is simple (exact-pose NCC, a naive Sobel, known joules),
 * and every error path (bad spec, NULL pointers, bad sizes) for its status and message.
 * Usage: test_capi TEMP_DIR (created if missing; the energy fixtures are written there). */
#define _POSIX_C_SOURCE 200809L /* pthread, mkdir under -std=c99 */
#include <errno.h>
#include <math.h>
#include <pthread.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

#include "cxx_reference.h"
#include "trn/trnkit.h"

static int checks = 0, failures = 0;

#define CHECK(cond, ...)                                          \
    do {                                                          \
        ++checks;                                                 \
        if (!(cond)) {                                            \
            ++failures;                                           \
            fprintf(stderr, "%s:%d: FAILED %s: ", __FILE__, __LINE__, #cond); \
            fprintf(stderr, __VA_ARGS__);                         \
            fprintf(stderr, "\n");                                \
        }                                                         \
    } while (0)

/* A failing call: its status and a message containing `text`. */
#define CHECK_FAILS(call, status, text)                                                                           \
    do {                                                                                                          \
        trn_status s_ = (call);                                                                                   \
        CHECK(s_ == (status), "%s returned %s, expected %s (%s)", #call, trn_status_name(s_), trn_status_name(status), \
              trn_last_error());                                                                                  \
        CHECK(strstr(trn_last_error(), (text)) != NULL, "%s: message '%s' lacks '%s'", #call, trn_last_error(), (text)); \
    } while (0)

#define CHECK_OK(call) CHECK((call) == TRN_OK, "%s: %s", #call, trn_last_error())

/* ---- inputs ------------------------------------------------------------------------------ */

enum { MAP_W = 200, MAP_H = 160, MAP_STRIDE = 208, T_W = 41, T_H = 31, T_X = 80, T_Y = 60, N_POSES = 48 };

static uint8_t map_pixels[MAP_H * MAP_STRIDE];
static float templ_f32[T_H * T_W];
static trn_pose poses[N_POSES];

/* A smooth deterministic texture (NCC needs structure, not noise) with padding bytes past the width. */
static void make_inputs(void) {
    int x, y, i;
    for (y = 0; y < MAP_H; ++y)
        for (x = 0; x < MAP_STRIDE; ++x)
            map_pixels[y * MAP_STRIDE + x] =
                x >= MAP_W ? 0xAB : (uint8_t)(128 + 60 * sin(x * 0.11 + y * 0.03) + 50 * cos(y * 0.17 - x * 0.05) + ((x * 7 + y * 13) % 11));
    for (y = 0; y < T_H; ++y)
        for (x = 0; x < T_W; ++x) templ_f32[y * T_W + x] = map_pixels[(T_Y + y) * MAP_STRIDE + T_X + x] + 0.25f;
    /* pose 0: exactly where the template was cut; then a spread of positions, headings and scales,
     * some half outside the map (too few samples). */
    poses[0].x = T_X + (T_W - 1) / 2.0f, poses[0].y = T_Y + (T_H - 1) / 2.0f, poses[0].yaw = 0, poses[0].scale = 1;
    for (i = 1; i < N_POSES; ++i) {
        poses[i].x = (float)(5 + (i * 37) % 190);
        poses[i].y = (float)(3 + (i * 53) % 155);
        poses[i].yaw = (float)(0.13 * i);
        poses[i].scale = (float)(0.8 + 0.01 * i);
    }
}

static trn_template templ_u8_view(void) {
    /* a view into the map itself: the template's stride is the map's */
    trn_template t;
    t.data = map_pixels + T_Y * MAP_STRIDE + T_X, t.type = TRN_PIXEL_U8, t.width = T_W, t.height = T_H, t.stride = MAP_STRIDE;
    return t;
}

/* ---- devices and backends ---------------------------------------------------------------- */

static void test_devices(trn_device_list** out_list) {
    char expected[4096], error[512], got[4096] = "";
    size_t i, used = 0;
    trn_device_list* list = NULL;
    trn_device_info info;
    CHECK(ref_device_names(expected, sizeof expected, error, sizeof error) == 0, "%s", error);
    CHECK_OK(trn_devices(&list));
    CHECK(trn_device_count(list) >= 2, "only %zu devices (cpu-ref and cpu are always there)", trn_device_count(list));
    for (i = 0; i < trn_device_count(list); ++i) {
        CHECK_OK(trn_device_get(list, i, &info));
        used += (size_t)snprintf(got + used, sizeof got - used, "%s\n", info.name);
        CHECK(strncmp(info.name, info.family, strlen(info.family)) == 0, "device %s of family %s", info.name, info.family);
    }
    CHECK(strcmp(got, expected) == 0, "C devices\n%s differ from C++\n%s", got, expected);
    CHECK_FAILS(trn_device_get(list, trn_device_count(list), &info), TRN_ERR_INVALID_ARGUMENT, "out of range");
    CHECK_FAILS(trn_device_get(list, 0, NULL), TRN_ERR_INVALID_ARGUMENT, "out is NULL");
    CHECK_FAILS(trn_devices(NULL), TRN_ERR_INVALID_ARGUMENT, "trn_devices: out is NULL");
    *out_list = list;
}

static int same_scores(const trn_score* a, const trn_score* b, size_t n, const char* what) {
    size_t i;
    for (i = 0; i < n; ++i)
        if (a[i].ncc != b[i].ncc || a[i].cc != b[i].cc || a[i].ssd != b[i].ssd || a[i].valid_samples != b[i].valid_samples ||
            a[i].flags != b[i].flags) {
            fprintf(stderr, "%s: pose %zu: C ncc %.9g cc %.9g ssd %.9g n %u flags %u, C++ ncc %.9g cc %.9g ssd %.9g n %u flags %u\n", what, i,
                    a[i].ncc, a[i].cc, a[i].ssd, a[i].valid_samples, a[i].flags, b[i].ncc, b[i].cc, b[i].ssd, b[i].valid_samples,
                    b[i].flags);
            return 0;
        }
    return 1;
}

static void test_scoring(const char* spec) {
    static const int32_t points[] = {0, 0, 40, 30, 20, 15, 3, 29, 39, 1, 10, 10, 30, 20, 5, 25};
    trn_backend* backend = NULL;
    trn_map* map = NULL;
    trn_device_info info;
    trn_score got[N_POSES], want[N_POSES];
    trn_times times;
    char error[512];
    int k, valid = 0, too_few = 0;
    size_t i;
    CHECK_OK(trn_backend_create(spec, &backend));
    if (!backend) return;
    CHECK_OK(trn_backend_info(backend, &info));
    CHECK(strcmp(info.name, spec) == 0, "backend %s reports name %s", spec, info.name);
    CHECK_OK(trn_map_upload(backend, map_pixels, MAP_W, MAP_H, MAP_STRIDE, &map));
    for (k = 0; k < 6; ++k) {
        trn_score_options o = trn_score_options_default();
        trn_template t = templ_u8_view();
        trn_plan* plan = NULL;
        if (k % 3 == 1) o.sampling = TRN_SAMPLING_RANDOM, o.fraction = 0.3, o.seed = 7;
        if (k % 3 == 2) o.sampling = TRN_SAMPLING_EXPLICIT, o.points = points, o.point_count = sizeof points / sizeof points[0] / 2;
        if (k >= 3) t.data = templ_f32, t.type = TRN_PIXEL_F32, t.stride = T_W;
        CHECK_OK(trn_plan_create(&t, &o, &plan));
        CHECK(k % 3 == 0 ? trn_plan_sample_count(plan) == (size_t)(T_W * T_H)
              : k % 3 == 2 ? trn_plan_sample_count(plan) == 8
                           : trn_plan_sample_count(plan) > 0 && trn_plan_sample_count(plan) < (size_t)(T_W * T_H),
              "plan %d has %zu samples", k, trn_plan_sample_count(plan));
        memset(got, 0xFF, sizeof got);
        CHECK_OK(trn_score_poses(backend, map, plan, poses, N_POSES, got, &times));
        CHECK(times.execute_ms >= 0, "execute_ms %g", times.execute_ms);
        CHECK(ref_score(spec, map_pixels, MAP_W, MAP_H, MAP_STRIDE, &t, &o, poses, N_POSES, want, error, sizeof error) == 0, "%s", error);
        CHECK(same_scores(got, want, N_POSES, spec), "%s: plan %d: C scores differ from C++", spec, k);
        CHECK(fabsf(got[0].ncc - 1.0f) < 1e-5f && got[0].flags == 0, "%s: plan %d: exact pose ncc %.7f flags %u", spec, k, got[0].ncc,
              got[0].flags);
        for (i = 0; i < N_POSES; ++i) valid += got[i].flags == 0, too_few += (got[i].flags & TRN_FLAG_TOO_FEW_SAMPLES) != 0;
        /* score(count 0) is a no-op that accepts NULL arrays */
        CHECK_OK(trn_score_poses(backend, map, plan, NULL, 0, NULL, NULL));
        trn_plan_destroy(plan);
    }
    CHECK(valid > 0 && too_few > 0, "%s: poses should include valid (%d) and too-few-samples (%d) ones", spec, valid, too_few);
    trn_backend_destroy(backend); /* the map keeps the backend alive; released with it */
    trn_map_destroy(map);
}

/* ---- no-data --------------------------------------------------------------------------- */

/* The left 60 columns and a square hole are no-data: scores where the patch avoids them equal the
 * unmasked ones, scores over them use fewer samples, and every backend gives cpu-ref's bits. */
static void test_masked(const char* spec) {
    enum { VALID_STRIDE = MAP_W + 3 };
    static uint8_t valid[MAP_H * VALID_STRIDE];
    trn_backend *backend = NULL, *ref = NULL;
    trn_map *masked = NULL, *plain = NULL, *ref_masked = NULL, *refused = NULL;
    trn_plan* plan = NULL;
    trn_score_options o = trn_score_options_default();
    trn_template t = templ_u8_view();
    trn_score got[N_POSES], unmasked[N_POSES], want[N_POSES];
    trn_localizer* localizer = NULL;
    trn_localizer_config config = trn_localizer_config_default();
    int x, y, fewer = 0;
    size_t i;
    for (y = 0; y < MAP_H; ++y)
        for (x = 0; x < VALID_STRIDE; ++x) valid[y * VALID_STRIDE + x] = (uint8_t)(x < 60 || (x >= 150 && x < 170 && y >= 20 && y < 40) ? 0 : 255);
    CHECK_OK(trn_backend_create(spec, &backend));
    CHECK_OK(trn_backend_create("cpu-ref", &ref));
    if (!backend || !ref) return;
    CHECK_OK(trn_map_upload_masked(backend, map_pixels, MAP_W, MAP_H, MAP_STRIDE, valid, VALID_STRIDE, &masked));
    CHECK_OK(trn_map_upload_masked(backend, map_pixels, MAP_W, MAP_H, MAP_STRIDE, NULL, 0, &plain));
    CHECK_OK(trn_map_upload_masked(ref, map_pixels, MAP_W, MAP_H, MAP_STRIDE, valid, VALID_STRIDE, &ref_masked));
    o.min_valid_fraction = 0.0;
    CHECK_OK(trn_plan_create(&t, &o, &plan));
    CHECK_OK(trn_score_poses(backend, masked, plan, poses, N_POSES, got, NULL));
    CHECK_OK(trn_score_poses(backend, plain, plan, poses, N_POSES, unmasked, NULL));
    CHECK_OK(trn_score_poses(ref, ref_masked, plan, poses, N_POSES, want, NULL));
    CHECK(same_scores(got, want, N_POSES, spec), "%s: masked scores differ from cpu-ref's", spec);
    CHECK(same_scores(got, unmasked, 1, spec), "%s: pose 0 avoids the no-data but its score changed", spec);
    for (i = 0; i < N_POSES; ++i) {
        CHECK(got[i].valid_samples <= unmasked[i].valid_samples, "%s: pose %zu uses more samples with the mask", spec, i);
        fewer += got[i].valid_samples < unmasked[i].valid_samples;
    }
    CHECK(fewer > 3, "%s: only %d poses lost samples to the no-data", spec, fewer);
    CHECK_FAILS(trn_map_upload_masked(backend, map_pixels, MAP_W, MAP_H, MAP_STRIDE, valid, 10, &refused), TRN_ERR_INVALID_ARGUMENT,
                "trn_map_upload_masked: valid stride 10 is smaller than its width 200");
    config.start_x = 120, config.start_y = 80;
    CHECK_OK(trn_localizer_create_masked(backend, map_pixels, MAP_W, MAP_H, MAP_STRIDE, valid, VALID_STRIDE, 1.0, &config, &localizer));
    trn_localizer_destroy(localizer);
    trn_plan_destroy(plan);
    trn_map_destroy(masked);
    trn_map_destroy(plain);
    trn_map_destroy(ref_masked);
    trn_backend_destroy(backend);
    trn_backend_destroy(ref);
}

/* ---- Sobel ------------------------------------------------------------------------------- */

static int reflect101(int i, int n) { return i < 0 ? -i : i >= n ? 2 * n - 2 - i : i; }

static void test_sobel(const char* spec) {
    enum { W = 37, H = 23, OUT_STRIDE = 45, GY_STRIDE = 40 }; /* strides differ: each must be honoured */
    static int16_t gx[H * OUT_STRIDE], gy[H * GY_STRIDE], rx[W * H], ry[W * H];
    const uint8_t* src = map_pixels + 10 * MAP_STRIDE + 20;
    trn_backend* backend = NULL;
    char error[512];
    int x, y, dx, dy, mismatches = 0, oracle = 0;
    CHECK_OK(trn_backend_create(spec, &backend));
    if (!backend) return;
    CHECK_OK(trn_sobel(backend, src, W, H, MAP_STRIDE, gx, OUT_STRIDE, gy, GY_STRIDE));
    CHECK(ref_sobel(spec, src, W, H, MAP_STRIDE, rx, ry, error, sizeof error) == 0, "%s", error);
    for (y = 0; y < H; ++y)
        for (x = 0; x < W; ++x) {
            int sx = 0, sy = 0;
            mismatches += gx[y * OUT_STRIDE + x] != rx[y * W + x] || gy[y * GY_STRIDE + x] != ry[y * W + x];
            for (dy = -1; dy <= 1; ++dy)
                for (dx = -1; dx <= 1; ++dx) {
                    const int v = src[reflect101(y + dy, H) * MAP_STRIDE + reflect101(x + dx, W)];
                    sx += dx * (2 - dy * dy) * v;
                    sy += dy * (2 - dx * dx) * v;
                }
            oracle += gx[y * OUT_STRIDE + x] != sx || gy[y * GY_STRIDE + x] != sy;
        }
    CHECK(mismatches == 0, "%s: %d Sobel pixels differ from the C++ API", spec, mismatches);
    CHECK(oracle == 0, "%s: %d Sobel pixels differ from the naive reflect-101 Sobel", spec, oracle);
    CHECK_FAILS(trn_sobel(backend, src, W, H, MAP_STRIDE, gx, W - 1, gy, GY_STRIDE), TRN_ERR_INVALID_ARGUMENT, "gx stride 36 is smaller");
    CHECK_FAILS(trn_sobel(backend, src, W, H, MAP_STRIDE, NULL, OUT_STRIDE, gy, GY_STRIDE), TRN_ERR_INVALID_ARGUMENT, "gx is NULL");
    CHECK_FAILS(trn_sobel(NULL, src, W, H, MAP_STRIDE, gx, OUT_STRIDE, gy, GY_STRIDE), TRN_ERR_INVALID_ARGUMENT, "backend is NULL");
    CHECK_FAILS(trn_sobel(backend, src, 0, H, MAP_STRIDE, gx, OUT_STRIDE, gy, GY_STRIDE), TRN_ERR_INVALID_ARGUMENT, "size 0x23");
    trn_backend_destroy(backend);
}

/* ---- energy ------------------------------------------------------------------------------ */

enum { N_FRAMES = 8 };
#define T0_NS 1700000000000000000LL
#define IDLE_W 2.0
#define BUSY_W 3.0

/* Timeline (ms from T0): lead idle, three sync bursts 300/100/200 ms, then N_FRAMES frames of
 * 200 ms with 100 ms idle gaps. Returns 1 when marker time t_ns lies in a busy row. */
struct row { const char* kind; int id; long long start_ms, end_ms; };
static struct row rows[32];
static int row_count = 0;

static void make_timeline(void) {
    long long t = 0;
    int i, idle = 0;
    const long long sync[3] = {300, 100, 200};
#define ADD(k, i_, len) (rows[row_count].kind = (k), rows[row_count].id = (i_), rows[row_count].start_ms = t, rows[row_count].end_ms = t + (len), t += (len), ++row_count)
    ADD("idle", idle++, 500);
    for (i = 0; i < 3; ++i) ADD("sync", i, sync[i]), ADD("idle", idle++, 100);
    for (i = 0; i < N_FRAMES; ++i) ADD("frame", i, 200), ADD("idle", idle++, i + 1 < N_FRAMES ? 100 : 500);
#undef ADD
}

static int busy_at_us(long long t_us) {
    int i;
    for (i = 0; i < row_count; ++i)
        if (strcmp(rows[i].kind, "idle") != 0 && t_us >= rows[i].start_ms * 1000 && t_us < rows[i].end_ms * 1000) return 1;
    return 0;
}

static int write_markers(const char* path) {
    FILE* f = fopen(path, "w");
    int i;
    if (!f) return 0;
    fprintf(f, "# trnkit-frames v1 backend=synthetic kernel=sobel\n"
               "kind,id,mono_start_ns,mono_end_ns,real_start_ns,real_end_ns,write_ms,exec_ms,read_ms\n");
    for (i = 0; i < row_count; ++i)
        fprintf(f, "%s,%d,%lld,%lld,%lld,%lld,0,0,0\n", rows[i].kind, rows[i].id, rows[i].start_ms * 1000000LL, rows[i].end_ms * 1000000LL,
                T0_NS + rows[i].start_ms * 1000000LL, T0_NS + rows[i].end_ms * 1000000LL);
    return fclose(f) == 0;
}

/* Power every millisecond on the UNIX clock, the log's clock `offset_ms` ahead of the markers'. */
static int write_power_log(const char* path, long long offset_ms) {
    FILE* f = fopen(path, "w");
    long long k, end_ms = rows[row_count - 1].end_ms;
    if (!f) return 0;
    fprintf(f, "# trnkit-power v1 kind=instant wall_clock=1\nt_s,power_w\n");
    for (k = -200; k <= end_ms + 200; ++k) {
        const long long ms = k + offset_ms + 1000; /* from T0 - 1 s, so never negative */
        fprintf(f, "%lld.%03lld,%.3f\n", T0_NS / 1000000000LL - 1 + ms / 1000, ms % 1000, IDLE_W + (busy_at_us(k * 1000) ? BUSY_W : 0));
    }
    return fclose(f) == 0;
}

static void test_energy_case(const char* log, const char* markers, int align_auto, double expect_offset) {
    trn_energy_options o = trn_energy_options_default();
    trn_energy_result* result = NULL;
    trn_energy_summary summary;
    trn_energy_frame frame;
    double gross[64], net[64], err[64], idle_w = 0, offset = 0;
    size_t samples[64], count = 0, i;
    int usable[64];
    char error[512];
    if (align_auto) o.align = TRN_ALIGN_AUTO;
    CHECK_OK(trn_energy_integrate(log, markers, &o, &result));
    if (!result) return;
    CHECK(ref_energy(log, markers, align_auto, 64, &count, gross, net, err, samples, usable, &idle_w, &offset, error, sizeof error) == 0,
          "%s", error);
    CHECK_OK(trn_energy_summary_get(result, &summary));
    CHECK(summary.frame_count == N_FRAMES && count == N_FRAMES, "frames: C %zu, C++ %zu, expected %d", summary.frame_count, count, N_FRAMES);
    CHECK(summary.usable_count == N_FRAMES, "usable %zu", summary.usable_count);
    CHECK(summary.idle_w == idle_w && summary.offset_s == offset, "idle %g/%g W, offset %g/%g s", summary.idle_w, idle_w, summary.offset_s,
          offset);
    CHECK(fabs(summary.offset_s - expect_offset) < 0.003, "offset %.6f s, expected %.3f", summary.offset_s, expect_offset);
    CHECK(fabs(summary.idle_w - IDLE_W) < 0.01, "idle %g W", summary.idle_w);
    for (i = 0; i < summary.frame_count && i < count; ++i) {
        CHECK_OK(trn_energy_frame_get(result, i, &frame));
        CHECK(frame.id == (int)i, "frame %zu has id %d", i, frame.id);
        CHECK(frame.gross_j == gross[i] && frame.net_j == net[i] && frame.error_j == err[i] && frame.samples == samples[i] &&
                  (frame.flag[0] == 0) == usable[i],
              "frame %zu: C %g/%g/%g J %zu samples '%s', C++ %g/%g/%g J %zu", i, frame.gross_j, frame.net_j, frame.error_j, frame.samples,
              frame.flag, gross[i], net[i], err[i], samples[i]);
        /* the truth: 3 W above idle for 200 ms */
        CHECK(fabs(frame.net_j - BUSY_W * 0.2) <= frame.error_j + 0.02, "frame %zu: net %g J, true %g J (bound %g)", i, frame.net_j,
              BUSY_W * 0.2, frame.error_j);
    }
    CHECK_FAILS(trn_energy_frame_get(result, N_FRAMES, &frame), TRN_ERR_INVALID_ARGUMENT, "out of range (8 frames)");
    CHECK(trn_energy_warning(result, summary.warning_count) == NULL, "warning past the end");
    trn_energy_result_destroy(result);
}

static void test_energy(const char* dir) {
    char log[1024], shifted[1024], markers[1024], missing[1024];
    trn_energy_options o = trn_energy_options_default();
    const char* bad_opts[] = {"nonsense"};
    trn_energy_result* result = (trn_energy_result*)&o; /* must be reset to NULL on failure */
    make_timeline();
    snprintf(log, sizeof log, "%s/power.csv", dir);
    snprintf(shifted, sizeof shifted, "%s/power-shifted.csv", dir);
    snprintf(markers, sizeof markers, "%s/markers.csv", dir);
    snprintf(missing, sizeof missing, "%s/no-such-log.csv", dir);
    CHECK(write_markers(markers) && write_power_log(log, 0) && write_power_log(shifted, 250), "cannot write fixtures in %s", dir);
    test_energy_case(log, markers, 0, 0.0);
    test_energy_case(shifted, markers, 1, 0.25);

    CHECK_FAILS(trn_energy_integrate(missing, markers, NULL, &result), TRN_ERR_FAILED, "no-such-log.csv");
    CHECK(result == NULL, "result not reset on failure");
    CHECK_FAILS(trn_energy_integrate(log, log, NULL, &result), TRN_ERR_FAILED, "power.csv:1");
    CHECK_FAILS(trn_energy_integrate(NULL, markers, NULL, &result), TRN_ERR_INVALID_ARGUMENT, "log_path is NULL");
    o.align = (trn_align_mode)7;
    CHECK_FAILS(trn_energy_integrate(log, markers, &o, &result), TRN_ERR_INVALID_ARGUMENT, "options->align 7");
    o = trn_energy_options_default();
    o.parse_options = bad_opts, o.parse_option_count = 1;
    CHECK_FAILS(trn_energy_integrate(log, markers, &o, &result), TRN_ERR_FAILED, "nonsense");
    o.parse_options = NULL;
    CHECK_FAILS(trn_energy_integrate(log, markers, &o, &result), TRN_ERR_INVALID_ARGUMENT, "parse_options is NULL");
}

/* ---- error paths of backends, maps, plans, scores ---------------------------------------- */

static void* fail_in_thread(void* arg) {
    trn_backend* b = NULL;
    (void)arg;
    return (void*)(size_t)(trn_backend_create("no-such-family", &b) == TRN_ERR_UNAVAILABLE &&
                           strstr(trn_last_error(), "no-such-family") != NULL);
}

static void test_errors(void) {
    trn_backend *cpu = NULL, *ref = NULL, *b = (trn_backend*)map_pixels;
    trn_map *map = NULL, *m = (trn_map*)map_pixels, *ref_map = NULL;
    trn_plan *plan = NULL, *p = (trn_plan*)map_pixels;
    trn_template t = templ_u8_view();
    trn_score_options o = trn_score_options_default();
    trn_score out[4];
    trn_pose bad[2];
    pthread_t thread;
    void* thread_ok = NULL;

    CHECK_FAILS(trn_backend_create("no-such-family", &b), TRN_ERR_UNAVAILABLE, "trn_backend_create: backend 'no-such-family' is not built");
    CHECK(b == NULL, "out not reset on failure");
    CHECK_FAILS(trn_backend_create("cpu-ref:7", &b), TRN_ERR_UNAVAILABLE, "cpu-ref:7");
    CHECK_FAILS(trn_backend_create(NULL, &b), TRN_ERR_INVALID_ARGUMENT, "spec is NULL");
    CHECK_FAILS(trn_backend_create("cpu", NULL), TRN_ERR_INVALID_ARGUMENT, "out is NULL");
    CHECK_FAILS(trn_backend_info(NULL, NULL), TRN_ERR_INVALID_ARGUMENT, "backend is NULL");
    CHECK_OK(trn_backend_create("cpu", &cpu));
    CHECK(strcmp(trn_last_error(), "") == 0, "message after success: '%s'", trn_last_error());
    CHECK_OK(trn_backend_create("cpu-ref", &ref));

    /* the message is per thread */
    CHECK_FAILS(trn_map_upload(cpu, NULL, 4, 4, 4, &m), TRN_ERR_INVALID_ARGUMENT, "trn_map_upload: pixels is NULL");
    CHECK(m == NULL, "out not reset on failure");
    CHECK(pthread_create(&thread, NULL, fail_in_thread, NULL) == 0 && pthread_join(thread, &thread_ok) == 0 && thread_ok,
          "failure in a thread");
    CHECK(strstr(trn_last_error(), "pixels is NULL") != NULL, "another thread's failure changed this thread's message: %s", trn_last_error());

    CHECK_FAILS(trn_map_upload(NULL, map_pixels, 4, 4, 4, &m), TRN_ERR_INVALID_ARGUMENT, "backend is NULL");
    CHECK_FAILS(trn_map_upload(cpu, map_pixels, -3, 4, 4, &m), TRN_ERR_INVALID_ARGUMENT, "pixels size -3x4 is not positive");
    CHECK_FAILS(trn_map_upload(cpu, map_pixels, 8, 4, 4, &m), TRN_ERR_INVALID_ARGUMENT, "pixels stride 4 is smaller than its width 8");
    CHECK_FAILS(trn_map_upload(cpu, map_pixels, 1, 1, 1, &m), TRN_ERR_FAILED, "smaller than 2x2");
    CHECK_FAILS(trn_map_upload(cpu, map_pixels, 70000, 2, 70000, &m), TRN_ERR_FAILED, "70000");
    CHECK_OK(trn_map_upload(cpu, map_pixels, MAP_W, MAP_H, MAP_STRIDE, &map));
    CHECK_OK(trn_map_upload(ref, map_pixels, MAP_W, MAP_H, MAP_STRIDE, &ref_map));

    CHECK_FAILS(trn_plan_create(NULL, NULL, &p), TRN_ERR_INVALID_ARGUMENT, "templ is NULL");
    CHECK(p == NULL, "out not reset on failure");
    t.width = 0;
    CHECK_FAILS(trn_plan_create(&t, NULL, &p), TRN_ERR_INVALID_ARGUMENT, "template size 0x31");
    t = templ_u8_view(), t.stride = 3;
    CHECK_FAILS(trn_plan_create(&t, NULL, &p), TRN_ERR_INVALID_ARGUMENT, "template stride 3");
    t = templ_u8_view(), t.type = (trn_pixel_type)9;
    CHECK_FAILS(trn_plan_create(&t, NULL, &p), TRN_ERR_INVALID_ARGUMENT, "templ->type 9");
    t = templ_u8_view(), o.sampling = TRN_SAMPLING_RANDOM, o.fraction = 1.5;
    CHECK_FAILS(trn_plan_create(&t, &o, &p), TRN_ERR_FAILED, "1.5");
    o = trn_score_options_default(), o.sampling = TRN_SAMPLING_EXPLICIT, o.point_count = 3;
    CHECK_FAILS(trn_plan_create(&t, &o, &p), TRN_ERR_INVALID_ARGUMENT, "options->points is NULL");
    o = trn_score_options_default(), o.sampling = (trn_sampling_kind)5;
    CHECK_FAILS(trn_plan_create(&t, &o, &p), TRN_ERR_INVALID_ARGUMENT, "options->sampling 5");
    CHECK_OK(trn_plan_create(&t, NULL, &plan));

    CHECK_FAILS(trn_score_poses(cpu, NULL, plan, poses, 1, out, NULL), TRN_ERR_INVALID_ARGUMENT, "map is NULL");
    CHECK_FAILS(trn_score_poses(cpu, map, NULL, poses, 1, out, NULL), TRN_ERR_INVALID_ARGUMENT, "plan is NULL");
    CHECK_FAILS(trn_score_poses(cpu, map, plan, NULL, 1, out, NULL), TRN_ERR_INVALID_ARGUMENT, "poses is NULL");
    CHECK_FAILS(trn_score_poses(cpu, map, plan, poses, 1, NULL, NULL), TRN_ERR_INVALID_ARGUMENT, "out is NULL");
    CHECK_FAILS(trn_score_poses(cpu, ref_map, plan, poses, 1, out, NULL), TRN_ERR_FAILED, "another backend");
    CHECK_FAILS(trn_score_poses(cpu, map, plan, poses, (size_t)1 << 40, out, NULL), TRN_ERR_FAILED, "count 1099511627776");
    CHECK_FAILS(trn_score_poses(cpu, map, plan, poses, (size_t)-1, out, NULL), TRN_ERR_FAILED, "count 9223372036854775807");
    o = trn_score_options_default(), o.sampling = TRN_SAMPLING_EXPLICIT, o.points = (const int32_t*)poses, o.point_count = (size_t)-1;
    CHECK_FAILS(trn_plan_create(&t, &o, &p), TRN_ERR_FAILED, "options->point_count 9223372036854775807");
    bad[0] = poses[0], bad[1] = poses[1], bad[1].scale = 0;
    CHECK_FAILS(trn_score_poses(cpu, map, plan, bad, 2, out, NULL), TRN_ERR_FAILED, "pose 1 has scale 0");
    bad[1].scale = 1, bad[1].x = NAN;
    CHECK_FAILS(trn_score_poses(cpu, map, plan, bad, 2, out, NULL), TRN_ERR_FAILED, "pose 1 has a non-finite x");

    CHECK(strcmp(trn_status_name(TRN_ERR_UNAVAILABLE), "TRN_ERR_UNAVAILABLE") == 0, "status name");
    CHECK(strlen(trn_version()) > 5 && strstr(trn_version(), "commit") != NULL, "version '%s'", trn_version());
    CHECK(trn_device_count(NULL) == 0 && trn_plan_sample_count(NULL) == 0, "NULL counts");
    /* destroying NULL is allowed */
    trn_backend_destroy(NULL), trn_map_destroy(NULL), trn_plan_destroy(NULL), trn_device_list_destroy(NULL), trn_energy_result_destroy(NULL);
    trn_plan_destroy(plan);
    trn_map_destroy(map), trn_map_destroy(ref_map);
    trn_backend_destroy(cpu), trn_backend_destroy(ref);
}

/* The localizer's C entry points: bad arguments named, no start refused at the first step, a step
 * without a frame propagates, a frame without its scale is refused, NULL destroy ignored. */
static void test_localizer(void) {
    trn_backend* cpu = NULL;
    trn_localizer* loc = NULL;
    trn_localizer_config c = trn_localizer_config_default();
    trn_observation o = trn_observation_default();
    trn_estimate e;
    CHECK_OK(trn_backend_create("cpu", &cpu));
    CHECK(isnan(c.start_x) && c.template_width == 160 && c.max_particles == 2000 && c.sparse == 1.0, "config defaults");
    CHECK_FAILS(trn_localizer_create(NULL, map_pixels, MAP_W, MAP_H, MAP_STRIDE, 0.5, &c, &loc), TRN_ERR_INVALID_ARGUMENT, "backend is NULL");
    CHECK_FAILS(trn_localizer_create(cpu, map_pixels, MAP_W, MAP_H, MAP_W - 1, 0.5, &c, &loc), TRN_ERR_INVALID_ARGUMENT, "stride");
    CHECK_FAILS(trn_localizer_create(cpu, map_pixels, MAP_W, MAP_H, MAP_STRIDE, 0, &c, &loc), TRN_ERR_FAILED, "metres_per_pixel");
    c.sparse = 2;
    CHECK_FAILS(trn_localizer_create(cpu, map_pixels, MAP_W, MAP_H, MAP_STRIDE, 0.5, &c, &loc), TRN_ERR_INVALID_ARGUMENT, "sparse");
    c.sparse = 1;
    c.conversion = "cubic";
    CHECK_FAILS(trn_localizer_create(cpu, map_pixels, MAP_W, MAP_H, MAP_STRIDE, 0.5, &c, &loc), TRN_ERR_FAILED, "cubic");
    c.conversion = NULL;
    CHECK(loc == NULL, "out not reset on failure");
    c.init_radius_m = 20, c.max_particles = 300;
    CHECK_OK(trn_localizer_create(cpu, map_pixels, MAP_W, MAP_H, MAP_STRIDE, 0.5, &c, &loc));
    CHECK_FAILS(trn_localizer_step(loc, &o, &e), TRN_ERR_FAILED, "start_x, start_y: required");
    trn_localizer_destroy(loc);
    loc = NULL;
    c.start_x = MAP_W / 2.0, c.start_y = MAP_H / 2.0;
    CHECK_OK(trn_localizer_create(cpu, map_pixels, MAP_W, MAP_H, MAP_STRIDE, 0.5, &c, &loc));
    o.odometry_east_m = 1, o.odometry_north_m = 0;
    CHECK_OK(trn_localizer_step(loc, &o, &e)); /* no frame: the particles move, nothing is scored */
    CHECK(e.frame_missing && e.particles > 0 && fabs(e.x - MAP_W / 2.0) < 40 / 0.5 && strcmp(e.lock_state, "none") == 0,
          "frameless step: missing %d particles %zu x %g lock %s", e.frame_missing, e.particles, e.x, e.lock_state);
    o.frame = map_pixels, o.width = T_W, o.height = T_H, o.stride = MAP_STRIDE;
    CHECK_FAILS(trn_localizer_step(loc, &o, &e), TRN_ERR_FAILED, "camera_hfov_deg"); /* neither scale nor camera */
    o.map_px_per_camera_px = 1;
    CHECK_FAILS(trn_localizer_step(loc, &o, &e), TRN_ERR_FAILED, "start_heading_rad"); /* compass mode, no heading ever */
    o.heading_rad = 0;
    CHECK_OK(trn_localizer_step(loc, &o, &e));
    CHECK(!e.frame_missing && e.particles > 0 && e.step_ms >= e.score_ms, "scored step: missing %d particles %zu", e.frame_missing, e.particles);
    CHECK_FAILS(trn_localizer_step(loc, NULL, &e), TRN_ERR_INVALID_ARGUMENT, "observation is NULL");
    /* Issue 43 item 2: the covariance (its trace is the spread), eph, no lat/lon without an origin,
     * velocity from two frame times. */
    CHECK(isnan(o.time_s) && isnan(c.map_origin_lat_deg) && isnan(c.map_origin_lon_deg), "time and origin default to NaN");
    CHECK(fabs(e.cov_ee_m2 + e.cov_nn_m2 - e.spread_m * e.spread_m) < 1e-6 * (1 + e.spread_m * e.spread_m) &&
              fabs(e.cov_ee_m2 - e.cov_xx_px2 * 0.25) < 1e-9 * (1 + e.cov_ee_m2) && fabs(e.cov_ne_m2 + e.cov_xy_px2 * 0.25) < 1e-9 * (1 + e.cov_ee_m2) &&
              e.eph_m * e.eph_m <= e.cov_ee_m2 + e.cov_nn_m2 + 1e-9 && isnan(e.latitude_deg) && isnan(e.vel_east_mps),
          "covariance: ee %g nn %g ne %g spread %g eph %g", e.cov_ee_m2, e.cov_nn_m2, e.cov_ne_m2, e.spread_m, e.eph_m);
    {
        trn_estimate e2;
        trn_observation t = trn_observation_default();
        t.odometry_east_m = 2, t.odometry_north_m = 0, t.heading_rad = 0, t.time_s = 5;
        CHECK_OK(trn_localizer_step(loc, &t, &e));
        t.time_s = 7;
        CHECK_OK(trn_localizer_step(loc, &t, &e2));
        CHECK(e2.time_s == 7 && fabs(e2.vel_east_mps - (e2.x - e.x) * 0.5 / 2) < 1e-12 && e2.vel_var_m2ps2 > 0,
              "velocity %g from x %g -> %g over 2 s", e2.vel_east_mps, e.x, e2.x);
    }
    /* Issue 43 item 4: a re-anchor on a new fix starts the filter over there (the config kept), the
     * lock unknown again until a fix; off the map and a radius that is none are refused. */
    {
        trn_observation t = trn_observation_default();
        const double fx = T_W / 2.0, fy = T_H / 2.0; /* the centre of the frame below: the map's top-left corner */
        CHECK_OK(trn_localizer_reanchor(loc, fx, fy, 5, 0));
        t.odometry_east_m = t.odometry_north_m = 0, t.heading_rad = 0;
        t.frame = map_pixels, t.width = T_W, t.height = T_H, t.stride = MAP_STRIDE, t.map_px_per_camera_px = 1;
        CHECK_OK(trn_localizer_step(loc, &t, &e));
        /* no fix vouches for the new place: "unknown", or "weak" on this periodic map (tests/filter and
         * tests/python check "unknown" on textured maps) */
        CHECK(hypot(e.x - fx, e.y - fy) < 5 / 0.5 && (strcmp(e.lock_state, "unknown") == 0 || strcmp(e.lock_state, "weak") == 0) &&
                  isnan(e.vel_east_mps),
              "re-anchored: (%g, %g) for (%g, %g), lock %s", e.x, e.y, fx, fy, e.lock_state);
        CHECK_FAILS(trn_localizer_reanchor(loc, -1000, fy, 5, NAN), TRN_ERR_INVALID_ARGUMENT, "px map");
        CHECK_FAILS(trn_localizer_reanchor(loc, fx, fy, 0, NAN), TRN_ERR_INVALID_ARGUMENT, "radius_m");
        CHECK_FAILS(trn_localizer_reanchor(NULL, fx, fy, 5, NAN), TRN_ERR_INVALID_ARGUMENT, "localizer is NULL");
    }
    trn_localizer_destroy(loc);
    loc = NULL;
    c.map_origin_lat_deg = 41.0;
    CHECK_FAILS(trn_localizer_create(cpu, map_pixels, MAP_W, MAP_H, MAP_STRIDE, 0.5, &c, &loc), TRN_ERR_INVALID_ARGUMENT, "go together");
    c.map_origin_lon_deg = -83.3;
    CHECK_OK(trn_localizer_create(cpu, map_pixels, MAP_W, MAP_H, MAP_STRIDE, 0.5, &c, &loc));
    o = trn_observation_default();
    CHECK_OK(trn_localizer_step(loc, &o, &e));
    CHECK(e.latitude_deg < 41.0 && e.latitude_deg > 40.99 && e.longitude_deg > -83.3 && e.longitude_deg < -83.29, "lat/lon %g %g",
          e.latitude_deg, e.longitude_deg);
    trn_localizer_destroy(loc);
    loc = NULL;
    c.map_origin_lat_deg = c.map_origin_lon_deg = NAN;
    /* No compass: a bad mode is named; a uniform yaw prior is wide, a Gaussian one narrow, and the
     * rotation increment turns the estimate. */
    CHECK(c.heading == NULL && isnan(o.odometry_yaw_rad), "heading defaults");
    c.heading = "north";
    CHECK_FAILS(trn_localizer_create(cpu, map_pixels, MAP_W, MAP_H, MAP_STRIDE, 0.5, &c, &loc), TRN_ERR_INVALID_ARGUMENT, "config->heading");
    c.heading = "none";
    o = trn_observation_default();
    o.odometry_east_m = 0, o.odometry_north_m = 1;
    CHECK_OK(trn_localizer_create(cpu, map_pixels, MAP_W, MAP_H, MAP_STRIDE, 0.5, &c, &loc));
    CHECK_OK(trn_localizer_step(loc, &o, &e));
    CHECK(e.yaw_sd > 2, "uniform yaw prior: spread %g rad", e.yaw_sd);
    trn_localizer_destroy(loc);
    loc = NULL;
    c.start_heading_rad = 1.0, c.start_heading_sd_deg = 3;
    CHECK_OK(trn_localizer_create(cpu, map_pixels, MAP_W, MAP_H, MAP_STRIDE, 0.5, &c, &loc));
    o.odometry_yaw_rad = 0.5;
    CHECK_OK(trn_localizer_step(loc, &o, &e));
    CHECK(fabs(e.yaw - 1.5) < 0.02 && e.yaw_sd < 0.1, "Gaussian yaw prior turned by 0.5 rad: yaw %g sd %g", e.yaw, e.yaw_sd);
    trn_localizer_destroy(loc);
    /* Profiles (issue 27): the dissertation's defaults; an unknown name refused naming both and
     * leaving *out alone; its steps equal the C++ Localizer's with localize::dissertation_profile()
     * bit for bit, and differ from ours; its lock monitor is off, ours on. */
    {
        trn_localizer_config d = trn_localizer_config_default(), kept;
        trn_observation f = trn_observation_default();
        CHECK(strcmp(d.profile, "ours") == 0 && d.lock_monitor == 1, "ours: profile %s lock monitor %d", d.profile, d.lock_monitor);
        CHECK_OK(trn_localizer_config_for_profile("dissertation", &d));
        CHECK(strcmp(d.profile, "dissertation") == 0 && d.lock_monitor == 0 && d.max_particles == 100000 && d.particles == 500,
              "dissertation: profile %s lock monitor %d max %zu particles %zu", d.profile, d.lock_monitor, d.max_particles, d.particles);
        kept = d;
        CHECK_FAILS(trn_localizer_config_for_profile("literal", &d), TRN_ERR_INVALID_ARGUMENT, "dissertation");
        CHECK(memcmp(&kept, &d, sizeof d) == 0, "*out changed by a refused profile");
        d.profile = "literal";
        CHECK_FAILS(trn_localizer_create(cpu, map_pixels, MAP_W, MAP_H, MAP_STRIDE, 0.5, &d, &loc), TRN_ERR_INVALID_ARGUMENT, "config->profile");
        d.profile = "dissertation";
        d.start_x = MAP_W / 2.0, d.start_y = MAP_H / 2.0, d.start_heading_rad = 0, d.init_radius_m = 20;
        f.frame = map_pixels, f.width = T_W, f.height = T_H, f.stride = MAP_STRIDE, f.map_px_per_camera_px = 1, f.heading_rad = 0;
        f.odometry_east_m = 1, f.odometry_north_m = 0;
        {
            double rx = NAN, ry = NAN, dx = NAN, dy = NAN;
            size_t rn = 0;
            char error[512] = "";
            CHECK(ref_dissertation_localizer(map_pixels, MAP_W, MAP_H, MAP_STRIDE, 0.5, d.start_x, d.start_y, 20, map_pixels, T_W, T_H,
                                             MAP_STRIDE, 1, 0, 3, &rx, &ry, &rn, error, sizeof error) == 0, "C++ reference: %s", error);
            CHECK_OK(trn_localizer_create(cpu, map_pixels, MAP_W, MAP_H, MAP_STRIDE, 0.5, &d, &loc));
            for (int i = 0; i < 3; ++i) CHECK_OK(trn_localizer_step(loc, &f, &e));
            CHECK(e.x == rx && e.y == ry && e.particles == rn && strcmp(e.lock_state, "none") == 0,
                  "dissertation via C: (%.17g, %.17g) %zu particles, lock %s; C++: (%.17g, %.17g) %zu", e.x, e.y, e.particles, e.lock_state,
                  rx, ry, rn);
            dx = e.x, dy = e.y;
            trn_localizer_destroy(loc);
            d = trn_localizer_config_default();
            d.start_x = MAP_W / 2.0, d.start_y = MAP_H / 2.0, d.start_heading_rad = 0, d.init_radius_m = 20;
            CHECK_OK(trn_localizer_create(cpu, map_pixels, MAP_W, MAP_H, MAP_STRIDE, 0.5, &d, &loc));
            for (int i = 0; i < 3; ++i) CHECK_OK(trn_localizer_step(loc, &f, &e));
            CHECK((e.x != dx || e.y != dy) && strcmp(e.lock_state, "none") != 0, "ours: (%g, %g), lock %s", e.x, e.y, e.lock_state);
            trn_localizer_destroy(loc);
            loc = NULL;
        }
    }
    trn_localizer_destroy(NULL);
    trn_backend_destroy(cpu); /* the localizer kept it alive until here */
    {
        trn_air_reader* r = NULL;
        trn_image* img = NULL;
        CHECK_FAILS(trn_air_reader_open("/nonexistent/air", &r), TRN_ERR_FAILED, "/nonexistent/air");
        CHECK_FAILS(trn_image_load("/nonexistent.png", &img), TRN_ERR_FAILED, "/nonexistent.png");
        CHECK(r == NULL && img == NULL, "out not reset on failure");
    }
}

/* Issue 43 item 4: visual odometry online. With config.visual_odometry a step without odometry (NaN)
 * takes it from its frame against the previous one: on a small synthetic flight (80x60 views of the
 * map moving 3 px east per step, scale 1, heading 0) every step after the first is "visual:features"
 * or "visual:phase" and the estimate follows the camera; odometry given is used as given ("given"). */
static void test_localizer_visual_odometry(void) {
    trn_backend* cpu = NULL;
    trn_localizer* loc = NULL;
    trn_localizer_config c = trn_localizer_config_default();
    trn_estimate e;
    int k;
    CHECK(c.visual_odometry == 0, "visual_odometry defaults to off, got %d", c.visual_odometry);
    CHECK_OK(trn_backend_create("cpu", &cpu));
    c.init_radius_m = 5, c.max_particles = 300, c.visual_odometry = 1;
    c.start_x = 20 + 39.5, c.start_y = 40 + 29.5, c.start_heading_rad = 0;
    CHECK_OK(trn_localizer_create(cpu, map_pixels, MAP_W, MAP_H, MAP_STRIDE, 0.5, &c, &loc));
    for (k = 0; k < 8; ++k) {
        trn_observation o = trn_observation_default();
        const int x = 20 + 3 * k, y = 40;
        o.frame = map_pixels + y * MAP_STRIDE + x, o.width = 80, o.height = 60, o.stride = MAP_STRIDE;
        o.map_px_per_camera_px = 1, o.heading_rad = 0;
        if (k == 7) o.odometry_east_m = 1.5, o.odometry_north_m = 0; /* given: used as given */
        CHECK_OK(trn_localizer_step(loc, &o, &e));
        if (k == 0) CHECK(strcmp(e.odometry_source, "visual:start") == 0, "step 0: odometry %s", e.odometry_source);
        else if (k == 7) CHECK(strcmp(e.odometry_source, "given") == 0, "step 7: odometry %s", e.odometry_source);
        else
            CHECK((strcmp(e.odometry_source, "visual:features") == 0 || strcmp(e.odometry_source, "visual:phase") == 0) && !e.odometry_lost,
                  "step %d: odometry %s, lost %d", k, e.odometry_source, e.odometry_lost);
    }
    CHECK(hypot(e.x - (20 + 21 + 39.5), e.y - (40 + 29.5)) < 6, "visual odometry online: (%g, %g) for (%g, %g)", e.x, e.y, 20 + 21 + 39.5,
          40 + 29.5);
    trn_localizer_destroy(loc);
    trn_backend_destroy(cpu);
}

int main(int argc, char** argv) {
    trn_device_list* list = NULL;
    trn_device_info info;
    char tested[512] = " ";
    size_t i;
    if (argc != 2) {
        fprintf(stderr, "usage: test_capi TEMP_DIR\n");
        return 2;
    }
    if (mkdir(argv[1], 0700) != 0 && errno != EEXIST) {
        fprintf(stderr, "test_capi: cannot create %s\n", argv[1]);
        return 2;
    }
    make_inputs();
    test_devices(&list);
    /* every family once: its first device */
    for (i = 0; i < trn_device_count(list); ++i) {
        char key[128];
        if (trn_device_get(list, i, &info) != TRN_OK) continue;
        snprintf(key, sizeof key, " %s ", info.family);
        if (strstr(tested, key)) continue;
        snprintf(tested + strlen(tested), sizeof tested - strlen(tested), "%s ", info.family);
        printf("test_capi: scoring and Sobel on %s (%s)\n", info.name, info.device);
        test_scoring(info.name);
        test_sobel(info.name);
        test_masked(info.name);
    }
    trn_device_list_destroy(list);
    test_errors();
    test_localizer();
    test_localizer_visual_odometry();
    test_energy(argv[1]);
    printf("test_capi: %d passed, %d failed\n", checks - failures, failures);
    return failures ? 1 : 0;
}
