/* The C encoder from C99 (any warning fails the build): one estimate, then a lost one, into `out`.
 * test_mavlink_capi.cpp compares the bytes with the C++ Stream's for the same estimates. */
#include <stdio.h>

#include "trn/trnkit.h"

size_t capi_mavlink_c_encode(uint8_t* out, size_t capacity) {
    trn_mavlink_options options = trn_mavlink_options_default();
    trn_mavlink_encoder* encoder;
    trn_nav_fix fix = trn_nav_fix_default();
    size_t size = 0, total = 0;
    options.system_id = 3;
    if (trn_mavlink_encoder_create(&options, &encoder) != TRN_OK) return 0;
    fix.time_us = 1700000000000000u;
    fix.valid = 1;
    fix.lat_deg = 41.0349018, fix.lon_deg = -83.3057413, fix.spread_m = 6.5, fix.north_m = 10, fix.east_m = -4;
    if (trn_mavlink_encode(encoder, &fix, out, capacity, &size) != TRN_OK) fprintf(stderr, "%s\n", trn_last_error());
    total += size;
    fix.valid = 0, fix.time_us += 200000;
    if (trn_mavlink_encode(encoder, &fix, out + total, capacity - total, &size) != TRN_OK) fprintf(stderr, "%s\n", trn_last_error());
    total += size;
    trn_mavlink_encoder_destroy(encoder);
    return total;
}
