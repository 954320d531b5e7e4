#include "trn/filter/backend_choice.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>

#include "trn/error.hpp"
#include "trn/registry.hpp"

namespace trn::filter {

std::unique_ptr<Backend> create_fastest_backend(const BackendOptions& options, std::vector<BackendTiming>* timings) {
    // A textured test map and template; timing only, the values do not matter.
    const int mw = 512, mh = 512, tw = 160, th = 120;
    std::vector<std::uint8_t> map(std::size_t(mw) * mh), templ(std::size_t(tw) * th);
    for (int y = 0; y < mh; ++y)
        for (int x = 0; x < mw; ++x) map[std::size_t(y) * mw + x] = static_cast<std::uint8_t>(128 + 60 * std::sin(x * 0.05) * std::cos(y * 0.07) + (x * 7 + y * 13) % 17);
    for (int y = 0; y < th; ++y)
        for (int x = 0; x < tw; ++x) templ[std::size_t(y) * tw + x] = map[std::size_t(y + 100) * mw + x + 100];
    std::vector<Pose> poses(1000);
    for (std::size_t i = 0; i < poses.size(); ++i) poses[i] = {200.0f + i % 50, 200.0f + i / 50 % 50, 0.01f * (i % 30), 1.4f};
    std::vector<ParticleScore> out(poses.size());

    std::vector<DeviceInfo> devices;
    for (const FamilyStatus& f : default_registry().status(options)) devices.insert(devices.end(), f.devices.begin(), f.devices.end());
    std::unique_ptr<Backend> chosen;  // the first usable one in preference order, never the quickest of this run
    for (const std::string& name : BackendRegistry::preferred_order(devices)) {
        std::unique_ptr<Backend> b;
        double ms = 0;
        try {
            b = default_registry().create(name, options);
            const MapHandle h = b->upload_map({map.data(), mw, mh, mw});
            const ScoringPlan plan = make_scoring_plan(GrayView{templ.data(), tw, th, tw}, {});
            b->score(h, plan, poses, out);  // warm-up: kernel builds, buffers
            const auto t0 = std::chrono::steady_clock::now();
            b->score(h, plan, poses, out);
            ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
        } catch (const Error&) {
            continue;  // listed but not usable: skip it, the others still compete
        }
        if (timings) timings->push_back({name, ms});
        if (!chosen) chosen = std::move(b);
    }
    if (!chosen) throw BackendUnavailable("no usable scoring backend in this build");
    return chosen;
}

}  // namespace trn::filter
