#include "trn/energy/sysfs_sampler.hpp"

#include <time.h>

#include <algorithm>
#include <filesystem>
#include <fstream>

#include "text_input.hpp"
#include "trn/error.hpp"

namespace trn::energy {
namespace fs = std::filesystem;
namespace {

std::string read_line(const fs::path& p) {
    std::ifstream f(p);
    std::string s;
    if (!f || !std::getline(f, s)) throw Error(p.string() + ": cannot read");
    return std::string(text::trim(s));
}

double read_number(const fs::path& p) {
    const std::string s = read_line(p);
    const auto v = text::to_number(s);
    if (!v) throw Error(p.string() + ": '" + s + "' is not a number");
    return *v;
}

unsigned long long read_counter(const fs::path& p) {
    const std::string s = read_line(p);
    std::size_t used = 0;
    unsigned long long v = 0;
    try {
        v = std::stoull(s, &used);
    } catch (const std::exception&) {
        used = 0;
    }
    if (used == 0 || used != s.size()) throw Error(p.string() + ": '" + s + "' is not a counter value");
    return v;
}

std::string name_of(const fs::path& dir) {
    std::error_code ec;
    return fs::exists(dir / "name", ec) ? read_line(dir / "name") : dir.filename().string();
}

std::string chan(const char* prefix, int n, const char* suffix) {
    std::string s(prefix);
    s.append(std::to_string(n)).append(suffix);
    return s;
}

}  // namespace

std::string SysfsSource::describe() const {
    return kind + ":" + name + (kind == "hwmon" ? ":" + std::to_string(channel) : "") + " (" + dir + ")";
}

std::vector<SysfsSource> list_sysfs_sources(const std::string& root) {
    std::vector<SysfsSource> out;
    std::error_code ec;
    const fs::path hw = fs::path(root) / "class/hwmon";
    if (fs::is_directory(hw, ec)) {
        std::vector<fs::path> dirs;
        for (const auto& e : fs::directory_iterator(hw, ec)) dirs.push_back(e.path());
        std::sort(dirs.begin(), dirs.end());
        for (const auto& d : dirs) {
            const std::string name = name_of(d);
            if (fs::exists(d / "power1_input", ec) && !fs::exists(d / "curr2_input", ec)) {
                out.push_back({"hwmon", d.string(), name, 1});
                continue;
            }
            for (int c = 1; c <= 8; ++c)
                if (fs::exists(d / chan("curr", c, "_input"), ec) && fs::exists(d / chan("in", c, "_input"), ec)) out.push_back({"hwmon", d.string(), name, c});
        }
    }
    const fs::path pc = fs::path(root) / "class/powercap";
    if (fs::is_directory(pc, ec)) {
        std::vector<fs::path> dirs;
        for (const auto& e : fs::directory_iterator(pc, ec)) dirs.push_back(e.path());
        std::sort(dirs.begin(), dirs.end());
        for (const auto& d : dirs)
            if (fs::exists(d / "energy_uj", ec)) out.push_back({"rapl", d.string(), name_of(d), 0});
    }
    return out;
}

SysfsSource find_sysfs_source(const std::string& spec, const std::string& root) {
    const auto parts = text::split(spec, ':');
    if (parts.size() < 2 || (parts[0] != "hwmon" && parts[0] != "rapl") || (parts[0] == "rapl" && parts.size() > 3) || parts.size() > 3)
        throw Error("source '" + spec + "': expected hwmon:NAME[:CHANNEL] or rapl:NAME");
    const std::string kind(parts[0]);
    std::string name(parts[1]);
    int channel = 0;
    if (kind == "hwmon" && parts.size() == 3) {
        const auto c = text::to_number(parts[2]);
        if (!c || *c < 1 || *c != static_cast<int>(*c)) throw Error("source '" + spec + "': channel must be a positive integer");
        channel = static_cast<int>(*c);
    } else if (kind == "rapl" && parts.size() == 3) {
        name.append(":").append(parts[2]);  // folder names like intel-rapl:0
    }
    const auto all = list_sysfs_sources(root);
    for (const auto& s : all)
        if (s.kind == kind && (s.name == name || fs::path(s.dir).filename() == name) && (channel == 0 || s.channel == channel)) return s;
    std::string have;
    for (const auto& s : all) {
        if (!have.empty()) have.append(", ");
        have.append(s.kind).append(":").append(s.name);
        if (s.kind == "hwmon") have.append(":").append(std::to_string(s.channel));
    }
    throw Error("source '" + spec + "' not found under " + root + " (found: " + (have.empty() ? "none" : have) + ")");
}

SysfsSampler::SysfsSampler(SysfsSource source) : source_(std::move(source)) {
    trace_.source = "sysfs:" + source_.dir;
    trace_.format = "trnkit";
    trace_.wall_clock = true;
    const fs::path d(source_.dir);
    std::error_code ec;
    if (source_.kind == "rapl") {
        trace_.kind = SampleKind::IntervalMean;
        trace_.quantity = "rapl:" + source_.name + " energy_uj";
        range_uj_ = fs::exists(d / "max_energy_range_uj", ec) ? read_counter(d / "max_energy_range_uj") : 0;
        if (range_uj_ == 0) trace_.notes.push_back("no max_energy_range_uj: a counter that steps back is an error, not a wrap");
        trace_.resolution_w = 0;
    } else if (source_.kind == "hwmon") {
        trace_.kind = SampleKind::Instant;
        const bool power = fs::exists(d / "power1_input", ec) && source_.channel == 1;
        trace_.quantity = power ? "hwmon:" + source_.name + " power1_input" : "hwmon:" + source_.name + chan(" in", source_.channel, "_input*") + chan("curr", source_.channel, "_input");
    } else {
        throw Error("sysfs source kind '" + source_.kind + "': expected hwmon or rapl");
    }
}

void SysfsSampler::poll(double t) {
    if (!trace_.t.empty() || have_counter_)
        if (!(t > last_t_)) throw Error(trace_.source + ": poll times must increase");
    const fs::path d(source_.dir);
    std::error_code ec;
    if (source_.kind == "rapl") {
        const unsigned long long uj = read_counter(d / "energy_uj");
        if (!have_counter_) {
            have_counter_ = true, last_uj_ = uj, last_t_ = t;
            trace_.first_interval_start = t;
            return;
        }
        unsigned long long delta = 0;
        if (uj >= last_uj_) {
            delta = uj - last_uj_;
        } else {
            if (range_uj_ == 0 || last_uj_ > range_uj_) throw Error((d / "energy_uj").string() + ": counter stepped back from " + std::to_string(last_uj_) + " to " + std::to_string(uj) + " with no valid max_energy_range_uj");
            delta = range_uj_ - last_uj_ + uj;  // wrapped past max_energy_range_uj
            ++wraps_;
        }
        trace_.t.push_back(t);
        trace_.w.push_back(static_cast<double>(delta) * 1e-6 / (t - last_t_));
        last_uj_ = uj, last_t_ = t;
        return;
    }
    double w = 0;
    if (source_.channel == 1 && fs::exists(d / "power1_input", ec)) {
        w = read_number(d / "power1_input") * 1e-6;  // microwatts
    } else {
        const double mv = read_number(d / chan("in", source_.channel, "_input")), ma = read_number(d / chan("curr", source_.channel, "_input"));
        w = mv * ma * 1e-6;
    }
    trace_.t.push_back(t);
    trace_.w.push_back(w);
    last_t_ = t;
}

PowerTrace SysfsSampler::trace() const {
    PowerTrace tr = trace_;
    if (wraps_) tr.notes.push_back(std::to_string(wraps_) + " energy counter wrap(s) unwrapped with max_energy_range_uj");
    return tr;
}

PowerTrace sample_sysfs(const SysfsSource& source, double period_s, double duration_s) {
    if (!(period_s > 0) || !(duration_s > 0)) throw Error("sample_sysfs: period and duration must be positive");
    SysfsSampler s(source);
    return sample_for(s, period_s, duration_s, SampleClock::Realtime);
}

}  // namespace trn::energy
