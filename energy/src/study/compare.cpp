#include "trn/energy/compare.hpp"

#include <cmath>
#include <cstdio>
#include <map>
#include <numeric>
#include <nlohmann/json.hpp>
#include <sstream>

#include "sha256.hpp"
#include "text_input.hpp"
#include "trn/error.hpp"
#include "trn/io/provenance.hpp"
#include "trn/io/outside_text.hpp"
#include "trn/detail/json_number.hpp"

namespace trn::energy {
namespace {

using nlohmann::json;

std::string fmt(const char* f, double v) {
    char buf[64];
    std::snprintf(buf, sizeof buf, f, v);
    return buf;
}
std::string g4(double v) { return fmt("%.4g", v); }

// The 95 % CI shown beside a platform's mean follows the unit of the tests: with runs as the unit
// it is the t-interval of the run means (frames of one run are not independent, so an interval
// over pooled frames would claim far more certainty than the tests do).
const Summary& ci_basis(const Comparison& c, const PlatformStats& p) {
    return c.unit == "runs" && p.run_means.n >= 2 ? p.run_means : p.energy;
}
// CSV: the number, or the bound "<1e-300" when it underflowed (never a 0 that reads as certainty).
std::string csv_p(double p) {
    if (std::isnan(p)) return "";
    if (!(p >= kSmallestReportedP)) return "<1e-300";
    return fmt("%.10g", p);
}

// JSON has no NaN/inf; a number that is not finite is written as null.
constexpr auto num = json_number<json>;
// A p-value that underflowed is written as the bound "< 1e-300", not as 0.
json pj(double p) { return p >= kSmallestReportedP ? json(p) : std::isnan(p) ? json(nullptr) : json("< 1e-300"); }

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

// Pooled SD of the frames about their own run's mean.
double within_run_sd(const std::vector<std::vector<double>>& runs) {
    double ss = 0;
    std::size_t df = 0;
    for (const auto& r : runs) {
        if (r.size() < 2) continue;
        const double m = std::accumulate(r.begin(), r.end(), 0.0) / static_cast<double>(r.size());
        for (double v : r) ss += (v - m) * (v - m);
        df += r.size() - 1;
    }
    return df ? std::sqrt(ss / static_cast<double>(df)) : 0.0;
}

const char* test_title(const std::string& t) { return t == "student" ? "Student" : "Welch"; }

}  // namespace

Comparison compare_runs(std::vector<RunInput> inputs, const CompareOptions& o) {
    if (inputs.empty()) throw Error("compare: no run reports given");
    refuse_repeats(inputs);
    Comparison c;
    c.options = o;
    std::map<std::string, std::size_t> index;
    std::vector<std::vector<std::vector<double>>> per_run;  // platform -> run -> frame energies
    for (const auto& in : inputs) {
        const auto& r = in.report;
        auto [it, fresh] = index.emplace(r.platform, c.platforms.size());
        if (fresh) {
            c.platforms.emplace_back();
            c.platforms.back().name = r.platform;
            per_run.emplace_back();
        }
        PlatformStats& p = c.platforms[it->second];
        ++p.runs;
        std::vector<double> run;
        for (const auto& f : r.frames) {
            if (!f.energy.flag.empty()) {
                ++p.flagged;
                continue;
            }
            run.push_back(1e3 * (o.net ? f.energy.net_j : f.energy.gross_j));
            p.energy_mj.push_back(run.back());
            p.frame_ms.push_back(f.marker_ms);
        }
        if (!run.empty()) p.run_mean_mj.push_back(std::accumulate(run.begin(), run.end(), 0.0) / static_cast<double>(run.size()));
        else c.notes.push_back(in.path + ": no usable frame; this run is left out");
        per_run[it->second].push_back(std::move(run));
    }
    c.inputs = std::move(inputs);
    bool all_multi = true;
    for (const auto& p : c.platforms) all_multi = all_multi && p.run_mean_mj.size() >= 2;
    const bool runs_unit = o.unit == TestUnit::Runs || (o.unit == TestUnit::Auto && all_multi);
    c.unit = runs_unit ? "runs" : "frames";
    if (runs_unit)
        c.notes.push_back("the run is the unit of the tests: each run's mean energy per frame is one value (frames of one run are not independent samples of the platform)");
    else
        for (const auto& p : c.platforms)
            if (p.run_mean_mj.size() >= 2) {
                c.notes.push_back("frames are the unit of the tests although some platform has several runs (--unit frames, or another platform has one run): "
                                  "between-run variation is not in the tests' error");
                break;
            } else if (p.runs == 1 && o.unit == TestUnit::Auto) {
                c.notes.push_back("one run per platform (" + p.name + "): frames are the unit, so the tests compare these runs; record several runs per platform to compare platforms");
                break;
            }
    auto sample = [&](const PlatformStats& p) -> const std::vector<double>& { return runs_unit ? p.run_mean_mj : p.energy_mj; };
    for (std::size_t k = 0; k < c.platforms.size(); ++k) {
        auto& p = c.platforms[k];
        p.energy = summarize(p.energy_mj);
        p.time = summarize(p.frame_ms);
        p.run_means = summarize(p.run_mean_mj);
        p.within_run_sd = within_run_sd(per_run[k]);
        try {
            const Normality nt = normality_test(sample(p));
            p.shapiro = nt.sw, p.shapiro_used = nt.used;
            if (nt.subsampled())
                c.notes.push_back(p.name + ": Shapiro-Wilk on a random subsample of 5000 of " + std::to_string(nt.n) +
                                  " values (its approximation holds to n = 5000; fixed seed 1)");
        } catch (const Error& e) {
            p.shapiro_note = e.what();
        }
    }
    std::vector<std::string> tests;
    if (o.both) tests = {"welch", "student"};
    else tests = {o.student ? "student" : "welch"};
    for (std::size_t i = 0; i < c.platforms.size(); ++i)
        for (std::size_t j = i + 1; j < c.platforms.size(); ++j) {
            PairStats ps;
            const PlatformStats &pa = c.platforms[i], &pb = c.platforms[j];
            ps.a = pa.name, ps.b = pb.name;
            const auto& a = sample(pa);
            const auto& b = sample(pb);
            ps.n_a = a.size(), ps.n_b = b.size();
            ps.normality_rejected = pa.normality_rejected(o.alpha) || pb.normality_rejected(o.alpha);
            for (const auto& t : tests) ps.t_tests.push_back({t, {}, 1});
            try {
                for (auto& t : ps.t_tests) t.t = t.test == "student" ? student_t_test(a, b) : welch_t_test(a, b);
                ps.ratio = ratio_of_means(a, b);
                ps.rank = mann_whitney_u(a, b);
                ps.bootstrap = bootstrap_ratio(a, b, o.bootstrap_resamples);
            } catch (const Error& e) {
                ps.note = e.what();
                for (auto& t : ps.t_tests) t.t = TTest{}, t.t.p = 1;
                ps.rank = RankTest{};
                ps.bootstrap.reset();
            }
            c.pairs.push_back(ps);
        }
    // Holm within each family of tests (each t-test kind, the rank test).
    for (std::size_t k = 0; k < tests.size(); ++k) {
        std::vector<double> raw;
        for (const auto& ps : c.pairs) raw.push_back(ps.t_tests[k].t.p);
        const auto adj = holm_adjust(raw);
        for (std::size_t q = 0; q < c.pairs.size(); ++q) c.pairs[q].t_tests[k].p_holm = adj[q];
    }
    std::vector<double> raw;
    for (const auto& ps : c.pairs) raw.push_back(ps.rank.p);
    const auto adj = holm_adjust(raw);
    for (std::size_t q = 0; q < c.pairs.size(); ++q) c.pairs[q].rank_p_holm = adj[q];
    for (const auto& p : c.platforms)
        if (p.normality_rejected(o.alpha))
            c.notes.push_back(p.name + ": Shapiro-Wilk rejects normality (p = " + format_p(p.shapiro->p) +
                              "): the t-test's p is approximate; read the Mann-Whitney U test and the bootstrap CI of the ratio beside it");
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
    os << "Unit of the tests: " << c.unit << ".\n";
    for (const auto& n : c.notes) os << "- " << n << "\n";
    os << "\n## Table 1: energy per frame (" << which << ", mJ) and frame time (ms)\n\n";
    if (c.unit == "runs") os << "The 95 % CI of energy is over the run means (the unit of the tests).\n\n";
    os << "| platform | runs | n | flagged | mean mJ | SD | median | IQR | 95 % CI | SD of run means | within-run SD | mean ms | SD ms | median ms | IQR ms | 95 % CI ms |\n";
    os << "|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|\n";
    for (const auto& p : c.platforms) {
        const auto &e = p.energy, &t = p.time;
        os << "| " << p.name << " | " << p.runs << " | " << e.n << " | " << p.flagged << " | " << g4(e.mean) << " | " << g4(e.sd) << " | " << g4(e.median)
           << " | " << g4(e.iqr()) << " | [" << g4(ci_basis(c, p).ci_low) << ", " << g4(ci_basis(c, p).ci_high) << "] | " << (p.run_means.n >= 2 ? g4(p.run_means.sd) : "-") << " | "
           << g4(p.within_run_sd) << " | " << g4(t.mean) << " | " << g4(t.sd) << " | " << g4(t.median) << " | " << g4(t.iqr()) << " | [" << g4(t.ci_low)
           << ", " << g4(t.ci_high) << "] |\n";
    }
    os << "\n## Table 2: Shapiro-Wilk normality test of energy per " << (c.unit == "runs" ? "run (run means)" : "frame") << " (alpha = " << c.options.alpha
       << ")\n\n";
    os << "| platform | n | tested | W | p | normal? |\n|---|---|---|---|---|---|\n";
    for (const auto& p : c.platforms) {
        const std::size_t n = c.unit == "runs" ? p.run_mean_mj.size() : p.energy.n;
        if (p.shapiro)
            os << "| " << p.name << " | " << n << " | " << p.shapiro_used << " | " << fmt("%.5f", p.shapiro->w) << " | " << format_p(p.shapiro->p) << " | "
               << (p.shapiro->p >= c.options.alpha ? "not rejected" : "**rejected**: use the rank test / bootstrap CI") << " |\n";
        else
            os << "| " << p.name << " | " << n << " | - | - | - | " << p.shapiro_note << " |\n";
    }
    os << "\n## Table 3: pairwise t-tests of energy per " << (c.unit == "runs" ? "run" : "frame") << " (Holm-adjusted per test)\n\n";
    os << "| A | B | test | n A | n B | mean A - B (mJ) | 95 % CI | t | df | p | p (Holm) | significant? | normality |\n";
    os << "|---|---|---|---|---|---|---|---|---|---|---|---|---|\n";
    for (const auto& s : c.pairs)
        for (const auto& tt : s.t_tests) {
            os << "| " << s.a << " | " << s.b << " | " << test_title(tt.test) << " | " << s.n_a << " | " << s.n_b << " | ";
            if (!s.note.empty()) {
                os << "- | - | - | - | - | - | " << s.note << " | - |\n";
                continue;
            }
            const TTest& t = tt.t;
            os << g4(t.diff) << " | [" << g4(t.ci_low) << ", " << g4(t.ci_high) << "] | " << fmt("%.3f", t.t) << " | " << fmt("%.1f", t.df) << " | "
               << format_p(t.p) << " | " << format_p(tt.p_holm) << " | " << (tt.p_holm < c.options.alpha ? "yes" : "no") << " | "
               << (s.normality_rejected ? "rejected: approximate" : "ok") << " |\n";
        }
    os << "\n## Table 4: Mann-Whitney U (Wilcoxon rank-sum) tests and energy ratios\n\n";
    os << "| A | B | W | P(A > B) | p | exact? | p (Holm) | significant? | ratio A/B | 95 % CI (delta) | 95 % CI (bootstrap) |\n";
    os << "|---|---|---|---|---|---|---|---|---|---|---|\n";
    for (const auto& s : c.pairs) {
        if (!s.note.empty()) {
            os << "| " << s.a << " | " << s.b << " | - | - | - | - | - | " << s.note << " | - | - | - |\n";
            continue;
        }
        os << "| " << s.a << " | " << s.b << " | " << g4(s.rank.w) << " | " << fmt("%.3f", s.rank.prob_superiority) << " | " << format_p(s.rank.p) << " | "
           << (s.rank.exact ? "exact" : "normal approx.") << " | " << format_p(s.rank_p_holm) << " | " << (s.rank_p_holm < c.options.alpha ? "yes" : "no")
           << " | " << fmt("%.4f", s.ratio.ratio) << " | [" << fmt("%.4f", s.ratio.ci_low) << ", " << fmt("%.4f", s.ratio.ci_high) << "] | ";
        if (s.bootstrap) os << "[" << fmt("%.4f", s.bootstrap->ci_low) << ", " << fmt("%.4f", s.bootstrap->ci_high) << "] |\n";
        else os << "- |\n";
    }
    return os.str();
}

std::string comparison_summary_text(const Comparison& c) {
    std::ostringstream os;
    os << "energy per frame (" << (c.options.net ? "net" : "gross") << ", mJ); tests on " << c.unit << "; 95 % CI over "
       << (c.unit == "runs" ? "run means" : "frames") << "\n";
    for (const auto& p : c.platforms) {
        os << "  " << p.name << ": " << g4(p.energy.mean) << " [" << g4(ci_basis(c, p).ci_low) << ", " << g4(ci_basis(c, p).ci_high) << "], " << p.energy.n
           << " frame(s) of " << p.runs << " run(s)";
        if (p.flagged) os << ", " << p.flagged << " flagged";
        if (p.shapiro) os << "; normality " << (p.normality_rejected(c.options.alpha) ? "REJECTED" : "not rejected") << " (p = " << format_p(p.shapiro->p) << ")";
        os << "\n";
    }
    for (const auto& s : c.pairs) {
        os << "  " << s.a << " vs " << s.b << ": ";
        if (!s.note.empty()) {
            os << "not tested (" << s.note << ")\n";
            continue;
        }
        os << "ratio " << fmt("%.4f", s.ratio.ratio);
        if (s.bootstrap) os << " (bootstrap 95 % CI [" << fmt("%.4f", s.bootstrap->ci_low) << ", " << fmt("%.4f", s.bootstrap->ci_high) << "])";
        for (const auto& t : s.t_tests) os << "; " << test_title(t.test) << " p(Holm) = " << format_p(t.p_holm);
        os << "; Mann-Whitney p(Holm) = " << format_p(s.rank_p_holm) << "\n";
    }
    for (const auto& n : c.notes) os << "  note: " << n << "\n";
    return os.str();
}

std::string energy_table_csv(const Comparison& c) {
    std::ostringstream os;
    os.precision(10);
    os << "platform,runs,n,flagged,energy_mean_mj,energy_sd_mj,energy_median_mj,energy_q1_mj,energy_q3_mj,energy_ci_low_mj,energy_ci_high_mj,"
          "time_mean_ms,time_sd_ms,time_median_ms,time_q1_ms,time_q3_ms,time_ci_low_ms,time_ci_high_ms,run_means_sd_mj,within_run_sd_mj\n";
    for (const auto& p : c.platforms) {
        const auto &e = p.energy, &t = p.time;
        os << '"' << p.name << "\"," << p.runs << "," << e.n << "," << p.flagged << "," << e.mean << "," << e.sd << "," << e.median << "," << e.q1 << "," << e.q3
           << "," << e.ci_low << "," << e.ci_high << "," << t.mean << "," << t.sd << "," << t.median << "," << t.q1 << "," << t.q3 << "," << t.ci_low
           << "," << t.ci_high << ",";
        if (p.run_means.n >= 2) os << p.run_means.sd;
        os << "," << p.within_run_sd << "\n";
    }
    return os.str();
}

std::string shapiro_table_csv(const Comparison& c) {
    std::ostringstream os;
    os.precision(10);
    os << "platform,unit,n,tested,w,p,note\n";
    for (const auto& p : c.platforms) {
        os << '"' << p.name << "\"," << c.unit << "," << (c.unit == "runs" ? p.run_mean_mj.size() : p.energy.n) << ",";
        if (p.shapiro) os << p.shapiro_used << "," << p.shapiro->w << "," << csv_p(p.shapiro->p) << ",\n";
        else os << ",,,\"" << p.shapiro_note << "\"\n";
    }
    return os.str();
}

std::string ttest_table_csv(const Comparison& c) {
    std::ostringstream os;
    os.precision(10);
    os << "a,b,test,unit,n_a,n_b,diff_mj,diff_ci_low,diff_ci_high,t,df,p,p_holm,ratio,ratio_ci_low,ratio_ci_high,normality_rejected,note\n";
    for (const auto& s : c.pairs)
        for (const auto& tt : s.t_tests) {
            os << '"' << s.a << "\",\"" << s.b << "\"," << tt.test << "," << c.unit << "," << s.n_a << "," << s.n_b << ",";
            if (!s.note.empty()) os << ",,,,,," << csv_p(tt.p_holm) << ",,,," << s.normality_rejected << ",\"" << s.note << "\"\n";
            else
                os << tt.t.diff << "," << tt.t.ci_low << "," << tt.t.ci_high << "," << tt.t.t << "," << tt.t.df << "," << csv_p(tt.t.p) << ","
                   << csv_p(tt.p_holm) << "," << s.ratio.ratio << "," << s.ratio.ci_low << "," << s.ratio.ci_high << "," << s.normality_rejected << ",\n";
        }
    return os.str();
}

std::string rank_ratio_table_csv(const Comparison& c) {
    std::ostringstream os;
    os.precision(10);
    os << "a,b,unit,n_a,n_b,mann_whitney_w,prob_a_greater,p,exact,p_holm,ratio,delta_ci_low,delta_ci_high,bootstrap_ci_low,bootstrap_ci_high,bootstrap_resamples,note\n";
    for (const auto& s : c.pairs) {
        os << '"' << s.a << "\",\"" << s.b << "\"," << c.unit << "," << s.n_a << "," << s.n_b << ",";
        if (!s.note.empty()) {
            os << ",,,,,,,,,,,\"" << s.note << "\"\n";
            continue;
        }
        os << s.rank.w << "," << s.rank.prob_superiority << "," << csv_p(s.rank.p) << "," << s.rank.exact << "," << csv_p(s.rank_p_holm) << "," << s.ratio.ratio
           << "," << s.ratio.ci_low << "," << s.ratio.ci_high << ",";
        if (s.bootstrap) os << s.bootstrap->ci_low << "," << s.bootstrap->ci_high << "," << s.bootstrap->resamples;
        else os << ",,";
        os << ",\n";
    }
    return os.str();
}

std::string comparison_json(const Comparison& c) {
    json j;
    j["trnkit_energy_comparison"] = 1;
    io::add_provenance(j);
    j["config"] = {{"test", c.options.both ? "welch+student" : c.options.student ? "student" : "welch"}, {"energy", c.options.net ? "net" : "gross"},
                   {"alpha", c.options.alpha}, {"correction", "holm (per test)"}, {"ci", 0.95}, {"unit", c.unit},
                   {"rank_test", "mann-whitney-u (as R wilcox.test)"}, {"bootstrap", {{"resamples", c.options.bootstrap_resamples}, {"seed", 1}, {"ci", "percentile"}}},
                   {"units", {{"energy", "mJ/frame"}, {"time", "ms/frame"}}}};
    j["notes"] = c.notes;
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
        json sw = p.shapiro ? json{{"w", num(p.shapiro->w)}, {"p", pj(p.shapiro->p)}, {"tested", p.shapiro_used}, {"rejected", p.normality_rejected(c.options.alpha)}}
                            : json{{"note", p.shapiro_note}};
        platforms.push_back({{"name", p.name}, {"runs", p.runs}, {"flagged", p.flagged}, {"energy_mj", summary_json(p.energy)},
                             {"run_means_mj", summary_json(p.run_means)}, {"within_run_sd_mj", num(p.within_run_sd)},
                             {"frame_ms", summary_json(p.time)}, {"shapiro_wilk", sw}});
    }
    j["platforms"] = platforms;
    json pairs = json::array();
    for (const auto& s : c.pairs) {
        json tests = json::array();
        for (const auto& tt : s.t_tests)
            tests.push_back({{"test", tt.test}, {"diff_mj", num(tt.t.diff)}, {"diff_ci95", {num(tt.t.ci_low), num(tt.t.ci_high)}}, {"t", num(tt.t.t)},
                             {"df", num(tt.t.df)}, {"p", pj(tt.t.p)}, {"p_holm", pj(tt.p_holm)}});
        json pair = {{"a", s.a}, {"b", s.b}, {"n_a", s.n_a}, {"n_b", s.n_b}, {"t_tests", tests}, {"normality_rejected", s.normality_rejected},
                     {"mann_whitney", {{"w", num(s.rank.w)}, {"prob_a_greater", num(s.rank.prob_superiority)}, {"p", pj(s.rank.p)}, {"exact", s.rank.exact},
                                       {"p_holm", pj(s.rank_p_holm)}}},
                     {"ratio", num(s.ratio.ratio)}, {"ratio_ci95_delta", {num(s.ratio.ci_low), num(s.ratio.ci_high)}}, {"note", s.note}};
        if (s.bootstrap) pair["ratio_ci95_bootstrap"] = {num(s.bootstrap->ci_low), num(s.bootstrap->ci_high)};
        pairs.push_back(pair);
    }
    j["pairs"] = pairs;
    return io::json_text(j, 1);  // outside text (input names, platforms, notes) made valid UTF-8 first
}

}  // namespace trn::energy
