#pragma once
// The largest inputs trnkit accepts, in one place, each with the reason for its value.
//
// Every place where a size enters (image files, Backend::upload_map / score / sobel, scoring plans,
// procedural maps, pose files, particle-filter settings) checks it here before any large
// allocation or work, so a too-large input fails at once with a trn::Error that names the input,
// its size, what it would need and the limit, instead of a late std::bad_alloc or an
// out-of-memory kill. docs/RELIABILITY.md ("Resource limits") lists them for users.
#include <cstdint>
#include <string>
#include <string_view>
#include "trn/export.hpp"

TRN_API_BEGIN
namespace trn::limits {

// Longest image side in pixels (maps, templates, frames, Sobel images). Map positions are floats:
// at 65536 px a float still resolves 1/128 px for the bilinear weights (at 2^24 px nothing is left).
inline constexpr std::int64_t kMaxImageSide = 65536;

// Most pixels in a map or any image file (2^30 = 1.07 Gpx, e.g. 32768x32768): OpenCV's own decode
// limit (OPENCV_IO_MAX_IMAGE_PIXELS defaults to 2^30), and about what eight Vulkan map bands of
// 128 MiB hold (the spec's minimum maxStorageBufferRange, which lavapipe has).
inline constexpr std::int64_t kMaxMapPixels = std::int64_t(1) << 30;

// Most pixels in a scoring template (2^24 = 16.8 Mpx, e.g. 4096x4096 or a 20 MP frame): the Vulkan
// sample table (up to 8 B per sample) then fits one 128 MiB storage buffer, the spec's minimum
// maxStorageBufferRange; building the plan takes up to 24 B per pixel on the host.
inline constexpr std::int64_t kMaxTemplatePixels = std::int64_t(1) << 24;

// Most particles in one score call, one pose file or one filter (2^22 = 4.2 M): the per-particle
// device sums (32 B each) then fit one 128 MiB storage buffer, the spec's minimum
// maxStorageBufferRange; each particle costs ~128 B on the host (pose, affine, sums, score).
inline constexpr std::int64_t kMaxParticles = std::int64_t(1) << 22;

// Memory each unit takes while it is being processed (the estimates behind the messages below).
// A backend's copy of an uploaded map is not here: each backend's layout defines its own
// (Backend::map_bytes; cpu-ref and OpenCL 1 B/px, cpu 2 B/px, Vulkan 4 B/px as quads or 1 B/px).
inline constexpr double kLoadBytesPerPixel = 2;       // OpenCV's decoded image + the GrayImage copy
inline constexpr double kGrayBytesPerPixel = 1;       // an 8-bit image held once (a generated map, a Sobel source's copy)
inline constexpr double kSobelBytesPerPixel = 5;      // 8-bit source + int16 gx and gy
inline constexpr double kTemplateBytesPerPixel = 24;  // double working value, float value, sample point, index
inline constexpr double kParticleBytes = 128;         // pose, affine, device sums, score

// No single input may need more than this share of physical memory: a command holds a few such
// buffers at once (a loaded map and a backend's copy), and more would swap or be killed.
inline constexpr double kMaxMemoryShare = 0.5;

// Physical memory of this machine (sysconf); 0 when it cannot be told (then only the fixed limits apply).
std::uint64_t physical_memory_bytes();

// "1.6 GB", "512 MB", "40 kB": decimal units, two significant digits or more.
std::string format_bytes(double bytes);

// The checks allocate nothing unless they throw (they run on every score and sobel call).
// Checks an image of w x h pixels against kMaxImageSide, max_pixels and the memory share
// (bytes_per_pixel * w * h). Throws trn::Error such as
//   "map.png: image 40000x40000 needs ~3.2 GB (limit 1073741824 pixels, e.g. 32768x32768)".
// `what` names the input ("upload_map: map", "big.png: image", "--size-m 90000").
void check_image(std::string_view what, std::int64_t width, std::int64_t height, std::int64_t max_pixels,
                 double bytes_per_pixel);

// Checks a count against `max` and the memory share (bytes_each * count). Throws trn::Error such as
//   "score: pose count 5000000 needs ~640 MB (limit 4194304)" (`what`: "score: pose count").
void check_count(std::string_view what, std::int64_t count, std::int64_t max, double bytes_each);

// Checks an estimate of `bytes` against kMaxMemoryShare of physical memory (`physical`: the
// machine's, or a stand-in for tests).
void check_memory(std::string_view what, double bytes, std::uint64_t physical = physical_memory_bytes());

}  // namespace trn::limits
TRN_API_END
