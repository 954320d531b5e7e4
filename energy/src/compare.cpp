#include "trn/energy/compare.hpp"

#include <cmath>
#include <cstdio>
#include <map>
#include <nlohmann/json.hpp>
#include <sstream>

#include "sha256.hpp"
#include "text_input.hpp"
#include "trn/error.hpp"

namespace trn::energy {
namespace {

using nlohmann::json;

std::string fmt(const char* f, double v) {
    char buf[64];
    std::snprintf(buf, sizeof buf, f, v);
    return buf;
}
std::string g4(double v) { return fmt("%.4g", v); }
std::string pval(double p) { return p < 1e-4 ? fmt("%.2e", p) : fmt("%.4f", p); }

// JSON has no NaN/inf; a number that is not finite is written as null.
json num(double v) { return std::isfinite(v) ? json(v) : json(nullptr); }

json summary_json(const Summary& s) {
    return {{"n", s.n}, {"mean", num(s.mean)}, {"sd", num(s.sd)}, {"median", num(s.median)}, {"q1", num(s.q1)}, {"q3", num(s.q3)},
            {"iqr", num(s.iqr())}, {"ci95_low", num(s.ci_low)}, {"ci95_high", num(s.ci_high)}};
}

// The same report twice (under any name), or two reports of one measurement (same log and
// markers), would pool its frames twice and double n: refused, naming both arguments.
void refuse_repeats(const std::vector<RunInput>& inputs) {
    for (std::size_t i = 0; i < inputs.size(); ++i)
        for (std::size_t j = i + 1; j < inputs.size(); ++j) {
            const RunInput &a = inputs[i], &b = inputs[j];
            if (!a.sha256.empty() && a.sha256 == b.sha256)
                throw Error("compare: " + a.path + " and " + b.path + " are the same run report (sha256 " + a.sha256.substr(0, 16) +
                            "...): its frames would be counted twice");
            const RunReport &ra = a.report, &rb = b.report;
            if (!ra.log_sha256.empty() && ra.log_sha256 == rb.log_sha256 && ra.markers_sha256 == rb.markers_sha256)
                throw Error("compare: " + a.path + " and " + b.path + " integrate the same measurement (log sha256 " + ra.log_sha256.substr(0, 16) +
                            "..., markers sha256 " + ra.markers_sha256.substr(0, 16) + "...): its frames would be counted twice");
        }
}

}  // namespace

Comparison compare_runs(std::vector<RunInput> inputs, const CompareOptions& o) {
    if (inputs.empty()) throw Error("compare: no run reports given");
    refuse_repeats(inputs);
    Comparison c;
    c.options = o;
    std::map<std::string, std::size_t> index;
    for (const auto& in : inputs) {
        const auto& r = in.report;
        auto [it, fresh] = index.emplace(r.platform, c.platforms.size());
        if (fresh) {
            c.platforms.emplace_back();
            c.platforms.back().name = r.platform;
        }
        PlatformStats& p = c.platforms[it->second];
        ++p.runs;
        for (const auto& f : r.frames) {
            if (!f.energy.flag.empty()) {
                ++p.flagged;
                continue;
            }
            p.energy_mj.push_back(1e3 * (o.net ? f.energy.net_j : f.energy.gross_j));
            p.frame_ms.push_back(f.marker_ms);
        }
    }
    c.inputs = std::move(inputs);
    for (auto& p : c.platforms) {
        p.energy = summarize(p.energy_mj);
        p.time = summarize(p.frame_ms);
        try {
            p.shapiro = shapiro_wilk(p.energy_mj);
        } catch (const Error& e) {
            p.shapiro_note = e.what();
        }
    }
    std::vector<double> raw;
    for (std::size_t i = 0; i < c.platforms.size(); ++i)
        for (std::size_t j = i + 1; j < c.platforms.size(); ++j) {
            PairStats ps;
            ps.a = c.platforms[i].name, ps.b = c.platforms[j].name;
            const auto& a = c.platforms[i].energy_mj;
            const auto& b = c.platforms[j].energy_mj;
            try {
                ps.t = o.student ? student_t_test(a, b) : welch_t_test(a, b);
                ps.ratio = ratio_of_means(a, b);
            } catch (const Error& e) {
                ps.note = e.what();
                ps.t.p = 1;
            }
            raw.push_back(ps.t.p);
            c.pairs.push_back(ps);
        }
    const auto adjusted = holm_adjust(raw);
    for (std::size_t k = 0; k < c.pairs.size(); ++k) c.pairs[k].p_holm = adjusted[k];
    return c;
}

Comparison compare_files(const std::vector<std::string>& paths, const CompareOptions& o) {
    std::vector<RunInput> inputs;
    for (const auto& path : paths) {
        const std::string report = text::read_file(path, text::kMaxSmallInputBytes);  // not for ever from a device
        inputs.push_back({path, sha256_hex(report), parse_run_report_json(report, path)});
    }
    return compare_runs(std::move(inputs), o);
}

std::string tables_markdown(const Comparison& c) {
    std::ostringstream os;
    const char* which = c.options.net ? "net (above idle)" : "gross";
    os << "## Table 1: energy per frame (" << which << ", mJ) and frame time (ms)\n\n";
    os << "| platform | runs | n | flagged | mean mJ | SD | median | IQR | 95 % CI | mean ms | SD ms | median ms | IQR ms | 95 % CI ms |\n";
    os << "|---|---|---|---|---|---|---|---|---|---|---|---|---|---|\n";
    for (const auto& p : c.platforms) {
        const auto &e = p.energy, &t = p.time;
        os << "| " << p.name << " | " << p.runs << " | " << e.n << " | " << p.flagged << " | " << g4(e.mean) << " | " << g4(e.sd) << " | " << g4(e.median)
           << " | " << g4(e.iqr()) << " | [" << g4(e.ci_low) << ", " << g4(e.ci_high) << "] | " << g4(t.mean) << " | " << g4(t.sd) << " | "
           << g4(t.median) << " | " << g4(t.iqr()) << " | [" << g4(t.ci_low) << ", " << g4(t.ci_high) << "] |\n";
    }
    os << "\n## Table 2: Shapiro-Wilk normality test of energy per frame (alpha = " << c.options.alpha << ")\n\n";
    os << "| platform | n | W | p | normal? |\n|---|---|---|---|---|\n";
    for (const auto& p : c.platforms) {
        if (p.shapiro)
            os << "| " << p.name << " | " << p.energy.n << " | " << fmt("%.5f", p.shapiro->w) << " | " << pval(p.shapiro->p) << " | "
               << (p.shapiro->p >= c.options.alpha ? "not rejected" : "rejected") << " |\n";
        else
            os << "| " << p.name << " | " << p.energy.n << " | - | - | " << p.shapiro_note << " |\n";
    }
    os << "\n## Table 3: pairwise " << (c.options.student ? "Student" : "Welch") << " t-tests of energy per frame (Holm-adjusted)\n\n";
    os << "| A | B | mean A - B (mJ) | 95 % CI | t | df | p | p (Holm) | significant? | energy ratio A/B | 95 % CI |\n";
    os << "|---|---|---|---|---|---|---|---|---|---|---|\n";
    for (const auto& s : c.pairs) {
        if (!s.note.empty()) {
            os << "| " << s.a << " | " << s.b << " | - | - | - | - | - | - | " << s.note << " | - | - |\n";
            continue;
        }
        os << "| " << s.a << " | " << s.b << " | " << g4(s.t.diff) << " | [" << g4(s.t.ci_low) << ", " << g4(s.t.ci_high) << "] | " << fmt("%.3f", s.t.t)
           << " | " << fmt("%.1f", s.t.df) << " | " << pval(s.t.p) << " | " << pval(s.p_holm) << " | " << (s.p_holm < c.options.alpha ? "yes" : "no")
           << " | " << fmt("%.4f", s.ratio.ratio) << " | [" << fmt("%.4f", s.ratio.ci_low) << ", " << fmt("%.4f", s.ratio.ci_high) << "] |\n";
    }
    return os.str();
}

std::string energy_table_csv(const Comparison& c) {
    std::ostringstream os;
    os.precision(10);
    os << "platform,runs,n,flagged,energy_mean_mj,energy_sd_mj,energy_median_mj,energy_q1_mj,energy_q3_mj,energy_ci_low_mj,energy_ci_high_mj,"
          "time_mean_ms,time_sd_ms,time_median_ms,time_q1_ms,time_q3_ms,time_ci_low_ms,time_ci_high_ms\n";
    for (const auto& p : c.platforms) {
        const auto &e = p.energy, &t = p.time;
        os << '"' << p.name << "\"," << p.runs << "," << e.n << "," << p.flagged << "," << e.mean << "," << e.sd << "," << e.median << "," << e.q1 << "," << e.q3
           << "," << e.ci_low << "," << e.ci_high << "," << t.mean << "," << t.sd << "," << t.median << "," << t.q1 << "," << t.q3 << "," << t.ci_low
           << "," << t.ci_high << "\n";
    }
    return os.str();
}

std::string shapiro_table_csv(const Comparison& c) {
    std::ostringstream os;
    os.precision(10);
    os << "platform,n,w,p,note\n";
    for (const auto& p : c.platforms) {
        os << '"' << p.name << "\"," << p.energy.n << ",";
        if (p.shapiro) os << p.shapiro->w << "," << p.shapiro->p << ",\n";
        else os << ",,\"" << p.shapiro_note << "\"\n";
    }
    return os.str();
}

std::string ttest_table_csv(const Comparison& c) {
    std::ostringstream os;
    os.precision(10);
    os << "a,b,test,diff_mj,diff_ci_low,diff_ci_high,t,df,p,p_holm,ratio,ratio_ci_low,ratio_ci_high,note\n";
    for (const auto& s : c.pairs) {
        os << '"' << s.a << "\",\"" << s.b << "\"," << (c.options.student ? "student" : "welch") << ",";
        if (!s.note.empty()) os << ",,,,,,," << s.p_holm << ",,,,\"" << s.note << "\"\n";
        else
            os << s.t.diff << "," << s.t.ci_low << "," << s.t.ci_high << "," << s.t.t << "," << s.t.df << "," << s.t.p << "," << s.p_holm << ","
               << s.ratio.ratio << "," << s.ratio.ci_low << "," << s.ratio.ci_high << ",\n";
    }
    return os.str();
}

std::string comparison_json(const Comparison& c) {
    json j;
    j["trnkit_energy_comparison"] = 1;
    j["config"] = {{"test", c.options.student ? "student" : "welch"}, {"energy", c.options.net ? "net" : "gross"}, {"alpha", c.options.alpha},
                   {"correction", "holm"}, {"ci", 0.95}, {"units", {{"energy", "mJ/frame"}, {"time", "ms/frame"}}}};
    json inputs = json::array();
    for (const auto& in : c.inputs) {
        const auto& r = in.report;
        inputs.push_back({{"path", in.path}, {"sha256", in.sha256}, {"platform", r.platform},
                          {"log", {{"path", r.log_path}, {"sha256", r.log_sha256}, {"format", r.log_format}, {"quantity", r.log_quantity},
                                   {"rate_hz", num(r.sampling.rate_hz)}, {"resolution_w", num(r.resolution_w)}}},
                          {"calibration", r.parse_options},
                          {"markers", {{"path", r.markers_path}, {"sha256", r.markers_sha256}, {"meta", r.marker_meta}}},
                          {"config", {{"rule", r.rule}, {"clock", r.clock}, {"align", r.align_mode}, {"min_samples", r.min_samples}}},
                          {"alignment", {{"offset_s", num(r.alignment.mapping.offset_s)}, {"drift", num(r.alignment.mapping.drift)},
                                         {"residual_s", num(r.alignment.residual_s)}, {"shift_minus_relative", num(r.shift.relative_minus)},
                                         {"shift_plus_relative", num(r.shift.relative_plus)}}},
                          {"idle_w", num(r.idle_w)}, {"warnings", r.warnings}});
    }
    j["inputs"] = inputs;
    json platforms = json::array();
    for (const auto& p : c.platforms) {
        json sw = p.shapiro ? json{{"w", num(p.shapiro->w)}, {"p", num(p.shapiro->p)}} : json{{"note", p.shapiro_note}};
        platforms.push_back({{"name", p.name}, {"runs", p.runs}, {"flagged", p.flagged}, {"energy_mj", summary_json(p.energy)},
                             {"frame_ms", summary_json(p.time)}, {"shapiro_wilk", sw}});
    }
    j["platforms"] = platforms;
    json pairs = json::array();
    for (const auto& s : c.pairs)
        pairs.push_back({{"a", s.a}, {"b", s.b}, {"diff_mj", num(s.t.diff)}, {"diff_ci95", {num(s.t.ci_low), num(s.t.ci_high)}}, {"t", num(s.t.t)},
                         {"df", num(s.t.df)}, {"p", num(s.t.p)}, {"p_holm", num(s.p_holm)}, {"ratio", num(s.ratio.ratio)},
                         {"ratio_ci95", {num(s.ratio.ci_low), num(s.ratio.ci_high)}}, {"note", s.note}});
    j["pairs"] = pairs;
    return j.dump(1) + "\n";
}

}  // namespace trn::energy
