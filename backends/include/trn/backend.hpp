#pragma once
// The one interface every compute backend implements (cpu-ref, cpu, opencl:<n>, vulkan:<n>).
//
// Public calls are non-virtual: they check their arguments by one set of rules, then hand over to
// the backend's do_* implementation, so every backend rejects the same bad input with the same
// message. Rules for scores are in scoring.hpp; Sobel is bit-exact with
// cv::Sobel(src, CV_16S, 1, 0 / 0, 1, 3) with BORDER_REFLECT_101.
// A backend object is not thread-safe: use one per thread. Repeated calls with the same inputs
// return bit-identical results.
#include <cstdint>
#include <memory>
#include <span>
#include <string>

#include "trn/error.hpp"
#include "trn/image.hpp"
#include "trn/scoring.hpp"
#include "trn/scoring_plan.hpp"
#include "trn/export.hpp"

TRN_API_BEGIN
namespace trn {

struct DeviceInfo {
    std::string name;     // what --backend takes: "cpu-ref", "cpu", "opencl:0", "vulkan:1"
    std::string family;   // "cpu-ref", "cpu", "opencl", "vulkan"
    std::string device;   // e.g. "pthread-haswell" or "NVIDIA H100"
    std::string type;     // "cpu", "gpu", "other"
    std::string driver;   // platform / driver name and version
    std::string details;  // free text: compute units, memory, subgroup size ...
};

class Backend;
struct CellMask;  // trn/impl/cell_mask.hpp (backend implementers)

// A map uploaded to one backend. Release it by dropping the handle.
class MapStorage {
public:
    MapStorage(const Backend* owner, int width, int height, bool masked = false)
        : owner_(owner), width_(width), height_(height), masked_(masked) {}
    virtual ~MapStorage() = default;
    int width() const { return width_; }
    int height() const { return height_; }
    const Backend* owner() const { return owner_; }
    // True when the map was uploaded with no-data (some bilinear cell holds an invalid pixel).
    bool masked() const { return masked_; }

private:
    const Backend* owner_;
    int width_, height_;
    bool masked_;
};
using MapHandle = std::shared_ptr<const MapStorage>;

class Backend {
public:
    virtual ~Backend() = default;
    virtual const DeviceInfo& info() const = 0;

    // Copies an 8-bit grey map to the backend: from 2x2 up to trn::limits::kMaxMapPixels (2^30)
    // pixels with sides up to kMaxImageSide (65536); a device may refuse less, naming its limit.
    MapHandle upload_map(GrayView map, PhaseTimes* times = nullptr);
    // The same with no-data: `valid` is the map's size, and pixel (x, y) is valid where
    // valid.at(x, y) != 0. A sample whose bilinear 2x2 cell holds an invalid pixel is left out of
    // every sum like a sample off the map (scoring.hpp); an empty view (data == nullptr) means every
    // pixel is valid, and so does a mask without an invalid pixel: the scores are then the bits of
    // the unmasked call. A mask that leaves no cell valid is refused.
    MapHandle upload_map(GrayView map, GrayView valid, PhaseTimes* times = nullptr);

    // Bytes this backend's copy of a width x height map takes, in the layout it really uses (its
    // device memory for GPUs, host memory for CPU devices): what upload_map checks against half of
    // physical memory and quotes in its messages. Arithmetic only: any positive size, nothing allocated.
    double map_bytes(std::int64_t width, std::int64_t height) const { return do_map_bytes(width, height); }

    // Scores every pose against the plan's template; out.size() must be >= poses.size() and
    // only the first poses.size() entries are written.
    void score(const MapHandle& map, const ScoringPlan& plan, std::span<const Pose> poses,
               std::span<ParticleScore> out, PhaseTimes* times = nullptr);
    // Convenience: builds the plan from the template and options first.
    void score(const MapHandle& map, const TemplateView& templ, std::span<const Pose> poses,
               const ScoreOptions& options, std::span<ParticleScore> out, PhaseTimes* times = nullptr);

    // 3x3 Sobel of src into gx and gy (each src-sized, strides may differ).
    void sobel(GrayView src, Int16View gx, Int16View gy, PhaseTimes* times = nullptr);

protected:
    // `mask` is null when every cell is valid; otherwise it outlives only the call (copy what is kept).
    virtual MapHandle do_upload_map(GrayView map, const CellMask* mask, PhaseTimes* times) = 0;
    // Defined beside the backend's map layout, from the same arithmetic that sizes its allocation
    // (without the mask: CellMask::bytes is added for a masked map).
    virtual double do_map_bytes(std::int64_t width, std::int64_t height) const = 0;
    virtual void do_score(const MapStorage& map, const ScoringPlan& plan, std::span<const Pose> poses,
                          std::span<ParticleScore> out, PhaseTimes* times) = 0;
    virtual void do_sobel(GrayView src, Int16View gx, Int16View gy, PhaseTimes* times) = 0;
};

}  // namespace trn
TRN_API_END
