// Backends, map upload and Sobel through the C API.
#include <string>

#include "c_handles.hpp"
#include "c_status.hpp"
#include "trn/registry.hpp"

using trn::capi::guarded;
using trn::capi::InvalidArgument;
using trn::capi::require_pointer;

namespace {

// The C-level shape checks of an image argument (the library checks limits and the rest).
void require_image(const void* data, int width, int height, std::ptrdiff_t stride, const std::string& what) {
    require_pointer(data, what.c_str());
    if (width <= 0 || height <= 0)
        throw InvalidArgument(what + " size " + std::to_string(width) + "x" + std::to_string(height) + " is not positive");
    if (stride < width)
        throw InvalidArgument(what + " stride " + std::to_string(stride) + " is smaller than its width " + std::to_string(width));
}

}  // namespace

extern "C" {

trn_status trn_backend_create(const char* spec, trn_backend** out) {
    return guarded(__func__, [&] {
        require_pointer(out, "out");
        *out = nullptr;
        require_pointer(spec, "spec");
        auto backend = std::make_unique<trn_backend>();
        backend->impl = trn::default_registry().create(spec);
        *out = backend.release();
    });
}

void trn_backend_destroy(trn_backend* backend) { delete backend; }

trn_status trn_backend_info(const trn_backend* backend, trn_device_info* out) {
    return guarded(__func__, [&] {
        require_pointer(backend, "backend");
        require_pointer(out, "out");
        *out = trn::capi::c_device_info(backend->impl->info());
    });
}

// Both uploads; errors name the function the caller called.
static trn_status upload_map(const char* function, trn_backend* backend, const uint8_t* pixels, int width, int height, ptrdiff_t stride,
                             const uint8_t* valid, ptrdiff_t valid_stride, trn_map** out) {
    return guarded(function, [&] {
        require_pointer(out, "out");
        *out = nullptr;
        require_pointer(backend, "backend");
        require_image(pixels, width, height, stride, "pixels");
        if (valid) require_image(valid, width, height, valid_stride, "valid");
        auto map = std::make_unique<trn_map>();
        map->backend = backend->impl;
        map->handle = backend->impl->upload_map(trn::GrayView{pixels, width, height, stride},
                                                valid ? trn::GrayView{valid, width, height, valid_stride} : trn::GrayView{});
        *out = map.release();
    });
}

trn_status trn_map_upload(trn_backend* backend, const uint8_t* pixels, int width, int height, ptrdiff_t stride, trn_map** out) {
    return upload_map(__func__, backend, pixels, width, height, stride, nullptr, 0, out);
}

trn_status trn_map_upload_masked(trn_backend* backend, const uint8_t* pixels, int width, int height, ptrdiff_t stride,
                                 const uint8_t* valid, ptrdiff_t valid_stride, trn_map** out) {
    return upload_map(__func__, backend, pixels, width, height, stride, valid, valid_stride, out);
}

void trn_map_destroy(trn_map* map) { delete map; }

trn_status trn_sobel(trn_backend* backend, const uint8_t* src, int width, int height, ptrdiff_t src_stride, int16_t* gx,
                     ptrdiff_t gx_stride, int16_t* gy, ptrdiff_t gy_stride) {
    return guarded(__func__, [&] {
        require_pointer(backend, "backend");
        require_image(src, width, height, src_stride, "src");
        require_image(gx, width, height, gx_stride, "gx");
        require_image(gy, width, height, gy_stride, "gy");
        backend->impl->sobel(trn::GrayView{src, width, height, src_stride}, trn::Int16View{gx, width, height, gx_stride},
                             trn::Int16View{gy, width, height, gy_stride});
    });
}

}  // extern "C"
