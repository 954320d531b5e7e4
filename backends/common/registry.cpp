// Backend registry: explicit families, device lookup by index or name, no silent fallback.
#include "trn/registry.hpp"

#include <algorithm>
#include <cctype>
#include <cstdlib>
#include <string>

#include "trn/parse_number.hpp"

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

std::vector<FamilyStatus> BackendRegistry::status() const {
    std::vector<FamilyStatus> out;
    for (const BackendFamily& f : families_) {
        FamilyStatus s{f.name, f.description, {}, {}};
        try {
            s.devices = f.list_devices(s.why_none);
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

std::unique_ptr<Backend> BackendRegistry::create(std::string_view spec) const {
    const std::size_t colon = spec.find(':');
    const std::string family_name(spec.substr(0, colon));
    std::string selector = colon == std::string_view::npos ? std::string() : std::string(spec.substr(colon + 1));

    const auto it = std::find_if(families_.begin(), families_.end(), [&](const BackendFamily& f) { return f.name == family_name; });
    if (it == families_.end()) {
        std::string known;
        for (const BackendFamily& f : families_) known += (known.empty() ? "" : ", ") + f.name;
        throw BackendUnavailable("backend '" + std::string(spec) + "' is not built into this trnkit (built: " + known + ")");
    }
    if (selector.empty() && !it->device_env.empty())
        if (const char* env = std::getenv(it->device_env.c_str()); env && *env) selector = env;

    std::string why;
    std::vector<DeviceInfo> devices;
    try {
        devices = it->list_devices(why);
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
    return it->create(index);
}

}  // namespace trn
