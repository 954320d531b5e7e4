// Argument checks shared by every backend: one set of rules, one set of messages.
#include "trn/backend.hpp"

#include <cmath>
#include <string>

#include "trn/impl/cell_mask.hpp"
#include "trn/limits.hpp"

namespace trn {
namespace {

template <typename T>
void check_view(const ImageView<T>& v, const char* call, const char* what) {
    if (v.data == nullptr || v.width <= 0 || v.height <= 0)
        throw Error(std::string(call) + ": " + what + " is empty");
    if (v.stride < v.width)
        throw Error(std::string(call) + ": " + what + " stride " + std::to_string(v.stride) +
                    " is smaller than its width " + std::to_string(v.width));
}

std::string size_text(int w, int h) { return std::to_string(w) + "x" + std::to_string(h); }

void check_pose(const Pose& p, std::size_t i) {
    const float fields[4] = {p.x, p.y, p.yaw, p.scale};
    const char* names[4] = {"x", "y", "yaw", "scale"};
    for (int k = 0; k < 4; ++k)
        if (!std::isfinite(fields[k]))
            throw Error("score: pose " + std::to_string(i) + " has a non-finite " + names[k] + " (" +
                        std::to_string(fields[k]) + ")");
    if (!(p.scale > 0))
        throw Error("score: pose " + std::to_string(i) + " has scale " + std::to_string(p.scale) +
                    "; it must be > 0");
}

}  // namespace

MapHandle Backend::upload_map(GrayView map, PhaseTimes* times) { return upload_map(map, GrayView{}, times); }

MapHandle Backend::upload_map(GrayView map, GrayView valid, PhaseTimes* times) {
    check_view(map, "upload_map", "map");
    if (map.width < 2 || map.height < 2)
        throw Error("upload_map: map " + size_text(map.width, map.height) + " is smaller than 2x2");
    const bool has_mask = valid.data != nullptr;
    if (has_mask) {
        check_view(valid, "upload_map", "validity mask");
        if (valid.width != map.width || valid.height != map.height)
            throw Error("upload_map: validity mask " + size_text(valid.width, valid.height) + " differs from the map " +
                        size_text(map.width, map.height));
    }
    // The backend's own layout decides the memory (cpu: vertical pixel pairs, 2 B/px; Vulkan quads:
    // 4 B/px), plus a bit per cell for no-data.
    const double pixels = double(map.width) * double(map.height);
    const double mask_bytes = has_mask ? CellMask::bytes(map.width, map.height) : 0.0;
    limits::check_image("upload_map: map", map.width, map.height, limits::kMaxMapPixels,
                        (map_bytes(map.width, map.height) + mask_bytes) / pixels);
    CellMask mask;
    if (has_mask) {
        mask = make_cell_mask(valid);
        if (mask.invalid_cells == std::int64_t(mask.cells_x) * mask.cells_y)
            throw Error("upload_map: the validity mask leaves no 2x2 cell of the " + size_text(map.width, map.height) +
                        " map with four valid pixels: nothing could be scored");
    }
    if (times) *times = {};
    return do_upload_map(map, has_mask && mask.invalid_cells > 0 ? &mask : nullptr, times);
}

void Backend::score(const MapHandle& map, const ScoringPlan& plan, std::span<const Pose> poses,
                    std::span<ParticleScore> out, PhaseTimes* times) {
    if (times) *times = {};
    if (!map) throw Error("score: no map; upload one with upload_map first");
    if (map->owner() != this)
        throw Error("score: the map was uploaded to another backend than " + info().name);
    if (plan.sample_count() == 0) throw Error("score: the scoring plan has no samples");
    if (map->width() < plan.width || map->height() < plan.height)
        throw Error("score: map " + size_text(map->width(), map->height()) + " is smaller than the template " +
                    size_text(plan.width, plan.height));
    limits::check_count("score: pose count", static_cast<std::int64_t>(poses.size()), limits::kMaxParticles,
                        limits::kParticleBytes);
    if (out.size() < poses.size())
        throw Error("score: output holds " + std::to_string(out.size()) + " scores for " +
                    std::to_string(poses.size()) + " poses");
    for (std::size_t i = 0; i < poses.size(); ++i) check_pose(poses[i], i);
    if (poses.empty()) return;
    do_score(*map, plan, poses, out, times);
}

void Backend::score(const MapHandle& map, const TemplateView& templ, std::span<const Pose> poses,
                    const ScoreOptions& options, std::span<ParticleScore> out, PhaseTimes* times) {
    score(map, make_scoring_plan(templ, options), poses, out, times);
}

void Backend::sobel(GrayView src, Int16View gx, Int16View gy, PhaseTimes* times) {
    check_view(src, "sobel", "source image");
    check_view(gx, "sobel", "gx output");
    check_view(gy, "sobel", "gy output");
    for (const Int16View* out : {&gx, &gy})
        if (out->width != src.width || out->height != src.height)
            throw Error("sobel: output " + size_text(out->width, out->height) + " differs from the source " +
                        size_text(src.width, src.height));
    // Outputs are the caller's, so only the backend's share (a band or a copy of the source) counts here.
    limits::check_image("sobel: image", src.width, src.height, limits::kMaxMapPixels, limits::kGrayBytesPerPixel);
    if (times) *times = {};
    do_sobel(src, gx, gy, times);
}

}  // namespace trn
