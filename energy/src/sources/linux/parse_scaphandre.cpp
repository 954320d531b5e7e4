// JSON power logs. Scaphandre's JSON exporter (`scaphandre json -f FILE`): one object per
// measurement step (JSON Lines, or one array of them) with the host's, each socket's and each
// RAPL domain's power in microwatts. Any other JSON is refused as JSON, not as a CSV that "needs a
// power column".
#include <cmath>
#include <nlohmann/json.hpp>
#include <string>

#include "option_reader.hpp"
#include "trace_builder.hpp"
#include "trn/energy/parsers.hpp"

namespace trn::energy {
namespace {

using json = nlohmann::json;

bool starts_json(std::string_view input) {
    const auto s = text::trim(input.substr(0, std::min<std::size_t>(input.size(), 256)));
    return !s.empty() && (s.front() == '{' || s.front() == '[');
}

// The reading `part` names in one step: host, socket:N or socket:N:DOMAIN. Returns false when
// the step does not hold it.
bool reading(const json& step, const std::string& part, double& t, double& uw) {
    auto number = [](const json& o, const char* key, double& out) {
        if (!o.is_object() || !o.contains(key) || !o[key].is_number()) return false;
        out = o[key].get<double>();
        return std::isfinite(out);
    };
    if (!step.is_object()) return false;
    if (part == "host") return step.contains("host") && number(step["host"], "consumption", uw) && number(step["host"], "timestamp", t);
    const auto parts = text::split(part, ':');
    if (!step.contains("sockets") || !step["sockets"].is_array()) return false;
    for (const auto& sock : step["sockets"]) {
        if (!sock.is_object() || !sock.contains("id") || !sock["id"].is_number() || std::to_string(sock["id"].get<long long>()) != parts[1]) continue;
        if (parts.size() == 2) return number(sock, "consumption", uw) && number(sock, "timestamp", t);
        if (!sock.contains("domains") || !sock["domains"].is_array()) return false;
        for (const auto& d : sock["domains"])
            if (d.is_object() && d.contains("name") && d["name"].is_string() && d["name"].get<std::string>() == parts[2])
                return number(d, "consumption", uw) && number(d, "timestamp", t);
    }
    return false;
}

}  // namespace

// '{' starts JSON; '[' only when the first line or the whole text is JSON (a log line such as
// "[2024-05-02 10:15:01] 5.1 W" is not).
bool looks_like_json(std::string_view input) {
    if (!starts_json(input)) return false;
    const auto s = text::trim(input);
    if (s.front() == '{') return true;
    const auto nl = s.find('\n');
    const auto first = text::trim(s.substr(0, nl));
    return json::accept(first.begin(), first.end()) || json::accept(s.begin(), s.end());
}

bool looks_like_scaphandre(std::string_view input) {
    if (!looks_like_json(input)) return false;
    const auto head = input.substr(0, std::min<std::size_t>(input.size(), 4096));
    return head.find("\"host\"") != std::string_view::npos && head.find("\"consumption\"") != std::string_view::npos;
}

PowerTrace parse_scaphandre(std::string_view input, const std::string& name, const ParseOptions& options) {
    const std::string parser = name + " (scaphandre)";
    OptionReader o(options, parser, {"part", "max_power_w"});
    const std::string part = o.text("part", "host");
    const auto pp = text::split(part, ':');
    if (!(part == "host" || (pp.size() >= 2 && pp.size() <= 3 && pp[0] == "socket" && text::to_number(pp[1]) && !pp.back().empty())))
        throw Error(parser + ": option part='" + part + "': expected host, socket:N or socket:N:DOMAIN (core, uncore, dram)");
    TraceBuilder b(name, "scaphandre");
    b.power_source(part == "host" ? "node" : "cpu", o);
    b.trace().kind = SampleKind::IntervalMean;
    b.trace().wall_clock = true;
    b.trace().quantity = part + " consumption (Scaphandre, uW; RAPL energy over each step)";
    std::size_t missing = 0;
    auto take = [&](const json& step, std::size_t line) {
        double t = 0, uw = 0;
        if (!reading(step, part, t, uw)) {
            if (missing++ == 0 && !step.is_object()) text::fail(name, line, "expected a JSON object (one Scaphandre measurement step)");
            b.drop(line, "step without a " + part + " consumption and timestamp");
            return;
        }
        b.add(line, t, uw * 1e-6);
    };
    const auto trimmed = text::trim(input);
    if (!trimmed.empty() && trimmed.front() == '[') {  // one array of steps
        const json all = json::parse(trimmed.begin(), trimmed.end(), nullptr, false);
        if (all.is_discarded() || !all.is_array()) text::fail(name, 1, "not valid JSON (an array of Scaphandre steps was expected)");
        for (const auto& step : all) take(step, 1);
    } else {  // JSON Lines
        for (const auto& l : text::split_lines(input)) {
            const auto s = text::trim(l.text);
            if (s.empty()) continue;
            const json step = json::parse(s.begin(), s.end(), nullptr, false);
            if (step.is_discarded()) text::fail(name, l.number, "not valid JSON (JSON Lines: one object per line)");
            take(step, l.number);
        }
    }
    b.note("Scaphandre consumption in microwatts, each the mean over the step before its timestamp (from RAPL energy); part=" + part);
    return b.finish();
}

}  // namespace trn::energy
