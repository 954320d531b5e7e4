#include "world.hpp"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <map>
#include <mutex>
#include <tuple>

#include "trn/error.hpp"
#include "trn/sim/map_ageing.hpp"
#include "trn/sim/render.hpp"

namespace trn::experiments {

std::uint64_t mix_seed(std::uint64_t a, std::uint64_t b) {
    Rng r(a ^ (b * 0xD1B54A32D192ED03ull + 0x8CB92BA72F3D8DD7ull));
    return r.next();
}

namespace {
std::mutex cache_mutex;
}

std::shared_ptr<const sim::Map> procedural_map(sim::TerrainStyle style, std::uint64_t seed, int year, double size_m) {
    static std::map<std::tuple<int, std::uint64_t, int, double>, std::shared_ptr<const sim::Map>> cache;
    const auto key = std::make_tuple(static_cast<int>(style), seed, year, size_m);
    std::lock_guard lock(cache_mutex);
    if (auto it = cache.find(key); it != cache.end()) return it->second;
    if (cache.size() > 8) cache.clear();  // maps are tens of MB; a study uses a few at a time
    sim::ProceduralMapOptions o;
    o.style = style;
    o.seed = seed;
    o.year = year;
    o.width_m = o.height_m = size_m;
    auto map = std::make_shared<const sim::Map>(sim::generate_procedural_map(o));
    cache[key] = map;
    return map;
}

std::string orthophoto_path(const std::string& shared_data) {
    if (shared_data.empty()) return "";
    const std::string path = shared_data + "/orthophoto.png";
    return std::filesystem::exists(path) ? path : "";
}

std::shared_ptr<const sim::Map> orthophoto_map(const std::string& path) {
    static std::map<std::string, std::shared_ptr<const sim::Map>> maps;
    std::lock_guard lock(cache_mutex);
    if (path.empty()) throw Error("experiment: no orthophoto (not in the shared data folder)");
    auto& map = maps[path];
    if (!map) map = std::make_shared<const sim::Map>(sim::load_map(path, kOrthophotoMetresPerPixel));
    return map;
}

std::shared_ptr<const sim::Map> aged_orthophoto(const std::string& path, double years, std::uint64_t seed) {
    static std::map<std::tuple<std::string, double, std::uint64_t>, std::shared_ptr<const sim::Map>> cache;
    const auto base = orthophoto_map(path);
    if (years <= 0) return base;
    std::lock_guard lock(cache_mutex);
    auto& slot = cache[{path, years, seed}];
    if (!slot) {
        sim::MapAgeingOptions o;
        o.years = years;
        o.seed = seed;
        slot = std::make_shared<const sim::Map>(sim::age_map(*base, o));
    }
    return slot;
}

GrayImage render_at(const sim::Map& map, const sim::Camera& camera, double x, double y, double yaw, double altitude_m,
                    std::uint64_t noise_seed) {
    sim::CameraPose pose;
    pose.map_x = x;
    pose.map_y = y;
    pose.yaw_rad = yaw;
    pose.altitude_m = altitude_m;
    sim::RenderOptions ro;
    ro.noise_seed = noise_seed;
    return sim::render_frame(map, camera, pose, ro);
}

void add_dissertation_noise(GrayImage& image, std::uint64_t seed, double salt, double pepper, double mean, double sigma) {
    Rng rng(seed);
    for (auto& p : image.pixels) {
        const double u = rng.uniform();
        double v = u < salt ? 255.0 : u < salt + pepper ? 0.0 : p;
        v += mean + sigma * rng.normal();
        p = static_cast<std::uint8_t>(std::lround(std::clamp(v, 0.0, 255.0)));
    }
}

MapPair study_map_pair(const std::string& orthophoto, std::uint64_t seed) {
    if (!orthophoto.empty()) return {orthophoto_map(orthophoto), aged_orthophoto(orthophoto, 2, seed)};
    return {procedural_map(sim::TerrainStyle::Forest, seed, 2008, 1200), procedural_map(sim::TerrainStyle::Forest, seed, 2010, 1200)};
}

}  // namespace trn::experiments
