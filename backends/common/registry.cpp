// Backend registry: explicit families, device lookup by index or name, no silent fallback.
#include "trn/registry.hpp"

#include <algorithm>
#include <cctype>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <string>

#include "trn/parse_number.hpp"
#include "trn/scoring_plan.hpp"

namespace trn {
namespace {

std::string lower(std::string s) {
    std::transform(s.begin(), s.end(), s.begin(), [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
    return s;
}

bool all_digits(std::string_view s) {
    return !s.empty() && std::all_of(s.begin(), s.end(), [](unsigned char c) { return std::isdigit(c); });
}

}  // namespace

void BackendRegistry::add(BackendFamily family) { families_.push_back(std::move(family)); }

std::vector<FamilyStatus> BackendRegistry::status(const BackendOptions& options) const {
    std::vector<FamilyStatus> out;
    for (const BackendFamily& f : families_) {
        FamilyStatus s{f.name, f.description, {}, {}};
        try {
            s.devices = f.list_devices(options, s.why_none);
        } catch (const std::exception& e) {
            s.devices.clear();
            s.why_none = e.what();
        }
        if (s.devices.empty() && s.why_none.empty()) s.why_none = "no devices found";
        out.push_back(std::move(s));
    }
    return out;
}

std::vector<std::string> BackendRegistry::available() const {
    std::vector<std::string> names;
    for (const FamilyStatus& s : status())
        for (const DeviceInfo& d : s.devices) names.push_back(d.name);
    return names;
}

std::unique_ptr<Backend> BackendRegistry::create(std::string_view spec, BackendOptions options) const {
    if (spec == "fastest") return create_fastest(std::move(options));
    const std::size_t colon = spec.find(':');
    const std::string family_name(spec.substr(0, colon));
    std::string selector = colon == std::string_view::npos ? std::string() : std::string(spec.substr(colon + 1));
    // "opencl:" names no device: refused rather than read as the family's first device.
    if (colon != std::string_view::npos && selector.empty())
        throw BackendUnavailable("backend '" + std::string(spec) + "': empty device after ':' (give an index or a name, e.g. " +
                                 family_name + ":0, or just " + family_name + ")");

    const auto it = std::find_if(families_.begin(), families_.end(), [&](const BackendFamily& f) { return f.name == family_name; });
    if (it == families_.end()) {
        std::string known;
        for (const BackendFamily& f : families_) known += (known.empty() ? "" : ", ") + f.name;
        throw BackendUnavailable("backend '" + std::string(spec) + "' is not built into this trnkit (built: " + known + ")");
    }
    if (selector.empty())
        if (const auto d = options.default_device.find(family_name); d != options.default_device.end()) selector = d->second;

    std::string why;
    std::vector<DeviceInfo> devices;
    try {
        devices = it->list_devices(options, why);
    } catch (const std::exception& e) {
        why = e.what();
    }
    if (devices.empty())
        throw BackendUnavailable("backend '" + std::string(spec) + "' is not available: " + (why.empty() ? "no devices found" : why));

    int index = -1;
    if (selector.empty()) {
        index = 0;
    } else if (all_digits(selector)) {
        // Overflow-safe: "vulkan:99999999999999999999" is an index out of range, not a stoi exception.
        const auto n = parse_whole_number(selector);
        if (!n || *n >= devices.size())
            throw BackendUnavailable("backend '" + std::string(spec) + "': device index " + selector + " out of range (" +
                                     std::to_string(devices.size()) + " device(s))");
        index = static_cast<int>(*n);
    } else {
        const std::string needle = lower(selector);
        for (std::size_t i = 0; i < devices.size() && index < 0; ++i)
            if (lower(devices[i].device).find(needle) != std::string::npos || lower(devices[i].driver).find(needle) != std::string::npos ||
                lower(devices[i].name) == needle)
                index = static_cast<int>(i);
        if (index < 0)
            throw BackendUnavailable("backend '" + std::string(spec) + "': no " + family_name + " device name or driver contains '" +
                                     selector + "'");
    }
    return it->create(index, options);
}

std::vector<std::string> BackendRegistry::preferred_order(const std::vector<DeviceInfo>& devices) {
    auto rank = [](const DeviceInfo& d) {
        if (d.type == "gpu") return d.family == "opencl" ? 0 : d.family == "vulkan" ? 1 : 2;
        if (d.family == "cpu") return 3;
        if (d.family == "cpu-ref") return 5;
        return 4;
    };
    std::vector<DeviceInfo> sorted = devices;
    std::stable_sort(sorted.begin(), sorted.end(), [&](const DeviceInfo& a, const DeviceInfo& b) {
        return rank(a) != rank(b) ? rank(a) < rank(b) : a.name < b.name;
    });
    std::vector<std::string> names;
    for (const DeviceInfo& d : sorted)
        if (d.family != "cpu-ref" || sorted.size() == 1) names.push_back(d.name);
    return names;
}

namespace {

// One realistic batch on `b` after a warm-up (kernel builds, buffers): a textured 512x512 map, a
// 160x120 template cut from it, 1000 particles. Timing only, the scores do not matter.
double time_one_batch(Backend& b) {
    const int mw = 512, mh = 512, tw = 160, th = 120;
    std::vector<std::uint8_t> map(std::size_t(mw) * mh), templ(std::size_t(tw) * th);
    for (int y = 0; y < mh; ++y)
        for (int x = 0; x < mw; ++x)
            map[std::size_t(y) * mw + x] = static_cast<std::uint8_t>(128 + 60 * std::sin(x * 0.05) * std::cos(y * 0.07) + (x * 7 + y * 13) % 17);
    for (int y = 0; y < th; ++y)
        for (int x = 0; x < tw; ++x) templ[std::size_t(y) * tw + x] = map[std::size_t(y + 100) * mw + x + 100];
    std::vector<Pose> poses(1000);
    for (std::size_t i = 0; i < poses.size(); ++i) poses[i] = {200.0f + i % 50, 200.0f + i / 50 % 50, 0.01f * (i % 30), 1.4f};
    std::vector<ParticleScore> out(poses.size());
    const MapHandle h = b.upload_map({map.data(), mw, mh, mw});
    const ScoringPlan plan = make_scoring_plan(GrayView{templ.data(), tw, th, tw}, {});
    b.score(h, plan, poses, out);  // warm-up
    const auto t0 = std::chrono::steady_clock::now();
    b.score(h, plan, poses, out);
    return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
}

}  // namespace

std::unique_ptr<Backend> BackendRegistry::create_fastest(BackendOptions options, std::vector<BackendTiming>* timings) const {
    std::vector<DeviceInfo> devices;
    for (const FamilyStatus& f : status(options)) devices.insert(devices.end(), f.devices.begin(), f.devices.end());
    std::unique_ptr<Backend> chosen;
    std::string why;
    for (const std::string& name : preferred_order(devices)) {
        try {
            std::unique_ptr<Backend> b = create(name, options);
            if (!timings) return b;
            timings->push_back({name, time_one_batch(*b)});
            if (!chosen) chosen = std::move(b);
        } catch (const Error& e) {  // listed but not usable (e.g. cannot build its kernels): the next one
            why += (why.empty() ? "" : "; ") + std::string(e.what());
        }
    }
    if (chosen) return chosen;
    throw BackendUnavailable("no usable backend for 'fastest'" + (why.empty() ? std::string() : ": " + why));
}

}  // namespace trn
