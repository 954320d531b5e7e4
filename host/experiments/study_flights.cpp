// The studies made of whole simulated flights localized by DPC-PFL:
//   conversion [3.5, Tables 3.7-3.12]: scenario presets x conversion functions x map ages x runs,
//     every cell averaged over the four map years as the dissertation does;
//   robustness [3.5.3, Table 3.12, Fig 3.7]: the parametric functions alone on the four map years;
//   odometry   [3.6, Figs 3.8-3.9]: filter vs visual-odometry error, final-error and slope ratios;
//     odometry-visual: the same with the odometry computed from the frames (visual_odometry.hpp),
//     also Table 3.13 [3.7] on its four presets (table_3_13.cpp).
// One job = one flight (preset, conversion, map age, run index). As in the dissertation (3.5.3: the
// flight imagery is of 2008, the maps of 2008-2014) the frames are rendered from the 2008 world and
// matched against the map of 2008 + map age, i.e. a map 0-6 years NEWER than the frames.
#include <algorithm>
#include <cmath>
#include <filesystem>
#include <map>

#include "dissertation_tables.hpp"
#include "flight_outputs.hpp"
#include "flight_settings.hpp"
#include "study.hpp"
#include "table.hpp"
#include "trn/localize/localization.hpp"
#include "trn/localize/report.hpp"
#include "table_3_13.hpp"
#include "world.hpp"

namespace trn::experiments {
namespace {

const std::vector<std::string>& kAllPresets = diss::scenario_names();
const std::vector<std::string>& kParametric = diss::parametric_functions();
constexpr int kFlightYear = 2008;

std::string safe_id(std::string s) {
    for (char& ch : s)
        if (ch == ':') ch = '_';
    return s;
}

// Shared settings of a flight sweep.
Json flight_config(bool quick) {
    return {{"distance_m", quick ? 400 : 2000}, {"rate_hz", 2}, {"template_width", quick ? 96 : 160}, {"nominal_size_m", quick ? 600 : 1600},
            {"flight_year", kFlightYear},
            // The filter's defaults are part of the configuration: job files made before the
            // displacement-vector motion model and the lock monitor (issue 12) are refused, not mixed.
            {"filter", kFilterDefaults},
            {"init_radius_m", filter::FilterConfig{}.init_radius_m}};  // trnkit experiment --init-radius-m
}

// One localization flight; writes the per-step CSV (and plots when asked) into the job folder.
// visual_odometry: the filter's odometry (and the baseline) is computed from the rendered frames.
Json fly(const Json& c, const std::string& preset_name, const std::string& conversion, int map_age, int run, JobContext& ctx,
         bool plots, bool visual_odometry = false) {
    sim::Scenario preset = sim::find_scenario(preset_name);
    preset.nominal_size_m = c.at("nominal_size_m");
    const double footprint = preset.max_altitude_m() / sim::Camera{}.focal_px() * 400 * 2;  // a '-wind' preset climbs
    const double size_m = std::ceil((preset.nominal_size_m * 1.1 + footprint + 100) / 100) * 100;
    const auto world = procedural_map(preset.terrain, ctx.seed, kFlightYear, size_m);
    const auto map = procedural_map(preset.terrain, ctx.seed, kFlightYear + map_age, size_m);

    sim::FlightConfig fc;
    fc.scenario = preset;
    fc.seed = mix_seed(ctx.seed, 100 + run);
    fc.frames = static_cast<std::size_t>(std::llround(c.at("distance_m").get<double>() / preset.speed_mps * preset.fps));
    localize::LocalizationSpec spec;
    spec.flight = localize::SimulatedFlight{world.get(), fc};
    spec.odometry = visual_odometry ? localize::OdometryKind::Visual : localize::OdometryKind::Recorded;
    spec.rate_hz = c.at("rate_hz").get<double>();
    spec.localizer.scoring.template_width = c.at("template_width");
    filter::FilterConfig& cfg = spec.localizer.filter;
    cfg = study_filter(c);
    cfg.metres_per_pixel = map->metres_per_pixel;
    cfg.conversion = filter::Conversion::parse(conversion);
    cfg.seed = mix_seed(ctx.seed, 200 + run);
    cfg.init_radius_m = c.at("init_radius_m");
    const localize::LocalizationResult r = localize::run_localization(spec, map->image.view(), map->metres_per_pixel, ctx.backend);
    const localize::LocalizationSummary& s = r.summary;
    std::filesystem::create_directories(ctx.job_folder);
    localize::write_rows_csv(ctx.job_folder + "/localization.csv", r.rows);
    if (plots) localize::plot_run(ctx.job_folder, r.rows, s, map->image.view(), map->metres_per_pixel, preset_name + " " + conversion);
    Json result = flight_result(s);
    result["particles_evaluated"] = s.mean_particles * s.steps;
    std::size_t most = 0;  // does the particle maximum bind? the largest set of any step
    for (const auto& row : r.rows) most = std::max(most, row.particles);
    result["max_particles_step"] = most;
    if (visual_odometry) {
        const auto& counts = r.run.visual_odometry_counts;
        result["visual_odometry_steps"] = {{"features", counts.features}, {"phase", counts.phase}, {"lost", counts.lost}};
    }
    return result;
}

std::vector<std::string> strings(const Json& j) { return j.get<std::vector<std::string>>(); }

int preset_index(const std::string& p) { return static_cast<int>(std::find(kAllPresets.begin(), kAllPresets.end(), p) - kAllPresets.begin()); }

// Both sweeps fly preset x function x map age x run; a job's id names all four
// ("UR-200-logistic_0.2-age4-3"), so one flight has the same id in either study. Runs are the
// outer loop: a batch of the first N jobs still to run (experiment-parallel --batch) gives every
// cell one more run before any cell gets the next, so a partial merge stays balanced.
std::vector<Json> flight_jobs(const Json& c) {
    std::vector<Json> out;
    for (int r = 0; r < c.at("runs").get<int>(); ++r)
        for (const auto& p : strings(c.at("presets")))
            for (const auto& f : strings(c.at("conversions")))
                for (int age : c.at("map_ages").get<std::vector<int>>())
                    out.push_back({{"id", p + "-" + safe_id(f) + "-age" + std::to_string(age) + "-" + std::to_string(r)},
                                   {"preset", p}, {"conversion", f}, {"map_age", age}, {"run", r}});
    return out;
}

// What fly() builds before the filter runs: the preset's world and its map of the job's age.
std::string flight_maps_key(const std::string& preset, int map_age) { return preset + "-age" + std::to_string(map_age); }

std::string signed_percent(double v) { return (v > 0 ? "+" : "") + percent(v, 1); }

std::string map_years(const Json& config) {
    std::string years;
    for (int a : config.at("map_ages").get<std::vector<int>>()) years += (years.empty() ? "" : "/") + std::to_string(kFlightYear + a);
    return years;
}

// "4" when every count is 4, else "2-4".
std::string count_range(int fewest, int most) { return fewest == most ? std::to_string(most) : std::to_string(fewest) + "-" + std::to_string(most); }

// What a cell of Tables 3.7-3.11 is the mean of: the configuration's runs x map years when every
// cell is whole, else the flights the cells actually hold (a partial merge), counted.
std::string flights_per_cell(const std::vector<Json>& o, const Json& config) {
    const int runs = config.at("runs").get<int>(), ages = static_cast<int>(config.at("map_ages").size());
    std::map<std::pair<std::string, std::string>, int> count;
    for (const auto& p : strings(config.at("presets")))
        for (const auto& f : strings(config.at("conversions"))) count[{p, f}] = 0;
    for (const Json& out : o) {
        const Json& p = out.at("params");
        if (const auto it = count.find({p.at("preset").get<std::string>(), p.at("conversion").get<std::string>()}); it != count.end()) ++it->second;
    }
    int fewest = runs * ages, most = 0;
    for (const auto& [cell, n] : count) fewest = std::min(fewest, n), most = std::max(most, n);
    const std::string design = std::to_string(runs) + " runs x " + std::to_string(ages) + " map years (" + map_years(config) + ")";
    if (fewest == runs * ages) return design;
    return count_range(fewest, most) + " of the " + std::to_string(runs * ages) + " flights of " + design;
}

// Table 3.12 and Fig 3.7 from every function of the configuration over the map ages.
std::string robustness_table(const std::vector<Json>& o, const MergeContext& mc) {
    const auto ages = mc.config.at("map_ages").get<std::vector<int>>();
    Table t;
    t.title = "Table 3.12: localization error over the maps of " + map_years(mc.config) + ", frames rendered from the " +
              std::to_string(kFlightYear) + " world (maps 0-" + std::to_string(ages.back()) +
              " years newer than the frames, as in the dissertation); SD over the map years of the mean error";
    t.header = {"Function", "SD m (ours)", "(diss.)", "Mean error m (ours)", "(diss.)", "RSD (ours)", "(diss.)", "Other-year loss (ours)"};
    std::vector<std::vector<double>> cols{{}};
    for (int a : ages) cols[0].push_back(kFlightYear + a);
    std::vector<std::string> titles;
    for (const auto& f : strings(mc.config.at("conversions"))) {
        std::vector<double> per_age;
        for (int a : ages) per_age.push_back(mean_of(o, "filter_mean_error_m", at_age("", f, a)));
        double mean = 0, var = 0;
        for (double v : per_age) mean += v / per_age.size();
        for (double v : per_age) var += (v - mean) * (v - mean) / (per_age.size() - 1);
        const double sd = std::sqrt(var);
        const auto k = std::find(kParametric.begin(), kParametric.end(), f) - kParametric.begin();
        const bool published = k < 10;
        t.rows.push_back({f, fmt(sd), published ? fmt(diss::kTable312[k].sd) : "-", fmt(mean), published ? fmt(diss::kTable312[k].accuracy) : "-",
                          percent(100 * sd / mean, 1), published ? percent(diss::kTable312[k].rsd, 1) : "-",
                          signed_percent(out_of_date_loss_percent(o, f))});
        cols.push_back(per_age);
        titles.push_back(f);
    }
    t.write(mc.out, "table_3_12");
    if (mc.plots)
        line_plot(mc.out + "/fig_3_7.png", "Fig 3.7: mean localization error vs map year (flight imagery " + std::to_string(kFlightYear) + ")",
                  "map year", "mean error (m)", cols, titles, {.x_tic_step = 2, .vertical_lines = {}});
    return t.markdown();
}

// The paper's and the abstract's summary claims, recomputed from the jobs (so they follow the sweep).
std::string claims_table(const std::vector<Json>& o, const MergeContext& mc, bool with_linear) {
    Table t;
    t.title = "Summary claims recomputed from these jobs (ours | diss.)";
    t.header = {"Claim", "Ours", "(diss.)"};
    const auto presets = strings(mc.config.at("presets"));
    if (with_linear) {
        const WinCount ours = scenarios_where_more_accurate(o, presets, "logistic:0.2", "linear");
        int published = 0;  // Table 3.10's positive "Logistic / Linear" cells over the same presets
        for (const auto& p : presets) published += diss::kTable310[preset_index(p)][1] > 0;
        t.rows.push_back({"Scenarios where logistic:0.2 is more accurate than linear", std::to_string(ours.wins) + " of " + std::to_string(ours.scenarios),
                          std::to_string(published) + " of " + std::to_string(presets.size()) + " (Table 3.10; paper: 10 of 12)"});
    }
    t.rows.push_back({"Mean error on the maps of other years vs the flight's own year (" + map_years(mc.config) + ", every function)",
                      signed_percent(out_of_date_loss_percent(o, "")),
                      "~30 % precision loss on out-of-date maps (paper abstract; per-year values only in Fig 3.7, not printed)"});
    t.write(mc.out, "table_claims");
    return t.markdown();
}

// Evidence that the printed Tables 3.7 and 3.8 carry each other's captions (dissertation_tables.hpp).
std::string label_check_table(const MergeContext& mc) {
    const diss::LabelCheck c = diss::check_family_labels();
    Table t;
    t.title = "Which printed table is which family: column means vs Table 3.12, re-ranking vs Table 3.9 (published numbers only)";
    t.header = {"Function", "Table 3.12 accuracy", "Column mean, captions as printed", "Column mean, swapped", "Table 3.9 score",
                "Re-ranked, as printed", "Re-ranked, swapped"};
    for (int f = 0; f < 10; ++f)
        t.rows.push_back({kParametric[f], fmt(diss::kTable312[f].accuracy), fmt(c.as_printed.column_means[f]), fmt(c.swapped.column_means[f]),
                          std::to_string(diss::kTable39Score[f]), std::to_string(c.as_printed.rank_sums[f]), std::to_string(c.swapped.rank_sums[f])});
    t.rows.push_back({"sum abs. difference / equal to the cent", "", fmt(c.as_printed.sum_abs_mean_difference) + " / " + std::to_string(c.as_printed.exact_means),
                      fmt(c.swapped.sum_abs_mean_difference) + " / " + std::to_string(c.swapped.exact_means), "max abs. difference",
                      std::to_string(c.as_printed.max_score_difference), std::to_string(c.swapped.max_score_difference)});
    t.write(mc.out, "table_label_check");
    return t.markdown();
}

// The conversion functions of the configuration, in `candidates` order.
std::vector<std::string> configured(const Json& config, const std::vector<std::string>& candidates) {
    const auto have = strings(config.at("conversions"));
    std::vector<std::string> out;
    for (const auto& f : candidates)
        if (std::find(have.begin(), have.end(), f) != have.end()) out.push_back(f);
    return out;
}

class ConversionStudy : public Study {
public:
    std::string name() const override { return "conversion"; }
    Json config(bool quick) const override {
        Json c = flight_config(quick);
        c["presets"] = quick ? std::vector<std::string>{"UR-200"} : kAllPresets;
        std::vector<std::string> f{"linear", "softmax"};
        // --quick: the baselines, the recommended function and each family's two ends on the
        // extreme map years, as many flights (12) as the single-map-year --quick had.
        if (quick)
            f.insert(f.end(), {"rectifying:0.2", "rectifying:-0.2", "logistic:0.2", "logistic:0.05"});
        else
            f.insert(f.end(), kParametric.begin(), kParametric.end());
        c["conversions"] = f;
        c["runs"] = quick ? 1 : 10;
        // Tables 3.7-3.11 average over the four map years (their column means are Table 3.12's).
        c["map_ages"] = quick ? std::vector<int>{0, 6} : std::vector<int>{0, 2, 4, 6};
        return c;
    }
    std::vector<Json> jobs(const Json& c) const override { return flight_jobs(c); }
    Json run_job(const Json& c, const Json& p, JobContext& ctx) const override {
        return fly(c, p.at("preset"), p.at("conversion"), p.at("map_age"), p.at("run"), ctx, false);
    }
    std::string inputs_key(const Json& p) const override { return flight_maps_key(p.at("preset"), p.at("map_age")); }
    std::string merge(const std::vector<Json>& o, const MergeContext& mc) const override {
        const auto presets = strings(mc.config.at("presets"));
        const std::string per_cell = flights_per_cell(o, mc.config);
        std::string md;
        for (const diss::Family fam : {diss::Family::Logistic, diss::Family::Rectifying}) {
            const bool logistic = fam == diss::Family::Logistic;
            const std::vector<std::string> family(kParametric.begin() + (logistic ? 5 : 0), kParametric.begin() + (logistic ? 10 : 5));
            Table t;
            t.title = std::string("Table 3.") + (logistic ? "7" : "8") + ": mean localization error (m), " + (logistic ? "logistic" : "rectifying") +
                      " conversion, mean of " + per_cell + " per cell (ours | diss.: the body printed as Table 3." + (logistic ? "8" : "7") +
                      ", whose caption is swapped; see the label check)";
            t.header = {"Scenario"};
            const auto functions = configured(mc.config, family);
            for (const auto& f : functions) {
                t.header.push_back(f + " (ours)");
                t.header.push_back("(diss.)");
            }
            for (const auto& p : presets) {
                std::vector<std::string> row{p};
                for (const auto& f : functions) {
                    row.push_back(fmt(mean_of(o, "filter_mean_error_m", {p, f})));
                    row.push_back(fmt(diss::mean_error(f, preset_index(p))));
                }
                t.rows.push_back(row);
            }
            t.write(mc.out, logistic ? "table_3_7" : "table_3_8");
            md += t.markdown() + "\n";
        }
        md += label_check_table(mc) + "\n";
        // Table 3.9: rank the configured parametric functions within each scenario (1 = most accurate).
        const auto ranked = configured(mc.config, kParametric);
        std::vector<std::vector<double>> errors;
        for (const auto& p : presets) {
            errors.emplace_back();
            for (const auto& f : ranked) errors.back().push_back(mean_of(o, "filter_mean_error_m", {p, f}));
        }
        const std::vector<int> score = diss::rank_sums(errors);
        std::vector<std::size_t> order(ranked.size());
        for (std::size_t k = 0; k < order.size(); ++k) order[k] = k;
        std::stable_sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) { return score[a] < score[b]; });
        Table r;
        r.title = "Table 3.9: conversion function ranking by accuracy (sum of per-scenario ranks of " + std::to_string(ranked.size()) +
                  " functions over " + std::to_string(presets.size()) + " scenario(s); the dissertation ranks 10 over 12)";
        r.header = {"Function", "Score (ours)", "Rank (ours)", "Score (diss.)", "Rank (diss.)"};
        for (std::size_t k = 0; k < ranked.size(); ++k) {
            const auto rank = std::find(order.begin(), order.end(), k) - order.begin() + 1;
            const auto d = std::find(kParametric.begin(), kParametric.end(), ranked[k]) - kParametric.begin();
            r.rows.push_back({ranked[k], fmt(score[k], 0), std::to_string(rank), std::to_string(diss::kTable39Score[d]), diss::kTable39Rank[d]});
        }
        r.write(mc.out, "table_3_9");
        md += r.markdown() + "\n";
        // Tables 3.10 and 3.11: logistic:0.2 and softmax against the baselines.
        for (int which = 0; which < 2; ++which) {
            const char* key = which ? "particles_evaluated" : "filter_mean_error_m";
            Table t;
            t.title = which ? "Table 3.11: speed-up in particles evaluated (base / new; ours | diss.)"
                            : "Table 3.10: accuracy improvement, (base error / new error - 1) x 100% (ours | diss.)";
            t.header = {"Scenario", "Softmax / Linear", "(diss.)", "Logistic 0.2 / Linear", "(diss.)", "Logistic 0.2 / Softmax", "(diss.)"};
            // Averages over the scenarios that have the flights, the published ones over the same
            // scenarios, so a partial sweep compares like with like.
            std::vector<double> sum(3, 0), pub(3, 0);
            std::vector<int> n(3, 0);
            for (const auto& p : presets) {
                const double lin = mean_of(o, key, {p, "linear"}), soft = mean_of(o, key, {p, "softmax"}), logi = mean_of(o, key, {p, "logistic:0.2"});
                const double v[3] = {which ? lin / soft : (lin / soft - 1) * 100, which ? lin / logi : (lin / logi - 1) * 100,
                                     which ? soft / logi : (soft / logi - 1) * 100};
                std::vector<std::string> row{p};
                for (int k = 0; k < 3; ++k) {
                    const double published = (which ? diss::kTable311 : diss::kTable310)[preset_index(p)][k];
                    row.push_back(which ? fmt(v[k]) : percent(v[k]));
                    row.push_back(which ? fmt(published) : percent(published));
                    if (std::isfinite(v[k])) sum[k] += v[k], pub[k] += published, ++n[k];
                }
                t.rows.push_back(row);
            }
            const int fewest = *std::min_element(n.begin(), n.end()), most = *std::max_element(n.begin(), n.end());
            std::vector<std::string> avg{most == static_cast<int>(presets.size()) && fewest == most
                                             ? std::string("Average")
                                             : "Average over the " + count_range(fewest, most) + " scenario(s) with flights (diss. over the same)"};
            for (int k = 0; k < 3; ++k) {
                avg.push_back(which ? fmt(sum[k] / n[k]) : percent(sum[k] / n[k]));
                avg.push_back(which ? fmt(pub[k] / n[k]) : percent(pub[k] / n[k]));
            }
            t.rows.push_back(avg);
            t.write(mc.out, which ? "table_3_11" : "table_3_10");
            md += t.markdown() + "\n";
        }
        // The same flights also give Table 3.12 (it is the robustness study's table over all functions).
        md += robustness_table(o, mc) + "\n";
        const Table spread = error_spread(o, strings(mc.config.at("conversions")));
        spread.write(mc.out, "table_error_spread");
        md += spread.markdown() + "\n";
        md += claims_table(o, mc, true);
        return md;
    }
};

class RobustnessStudy : public Study {
public:
    std::string name() const override { return "robustness"; }
    Json config(bool quick) const override {
        Json c = flight_config(quick);
        c["presets"] = quick ? std::vector<std::string>{"UR-200"} : kAllPresets;
        c["conversions"] = quick ? std::vector<std::string>{"rectifying:0.2", "logistic:0.05"} : kParametric;
        c["map_ages"] = std::vector<int>{0, 2, 4, 6};
        c["runs"] = quick ? 1 : 10;
        return c;
    }
    std::vector<Json> jobs(const Json& c) const override { return flight_jobs(c); }
    Json run_job(const Json& c, const Json& p, JobContext& ctx) const override {
        return fly(c, p.at("preset"), p.at("conversion"), p.at("map_age"), p.at("run"), ctx, false);
    }
    std::string inputs_key(const Json& p) const override { return flight_maps_key(p.at("preset"), p.at("map_age")); }
    std::string merge(const std::vector<Json>& o, const MergeContext& mc) const override {
        return robustness_table(o, mc) + "\n" + claims_table(o, mc, false);
    }
    // Its flights are the conversion study's parametric ones (fly() reads nothing else of the configuration).
    std::string flights_shared_with() const override { return "conversion"; }
};

// `odometry` flies the twelve presets as published; `odometry-wind` their '-wind' twins (crab,
// climbs, barometer, drifting odometry: sim/scenario.hpp), where the odometry is worse;
// `odometry-visual` the twelve presets with the odometry computed from the frames (issue 17).
class OdometryStudy : public Study {
public:
    OdometryStudy(bool wind, bool visual) : wind_(wind), visual_(visual) {}
    std::string name() const override { return visual_ ? "odometry-visual" : wind_ ? "odometry-wind" : "odometry"; }
    Json config(bool quick) const override {
        Json c = flight_config(quick);
        std::vector<std::string> presets = quick ? std::vector<std::string>{"FR-200"} : kAllPresets;
        if (wind_)
            for (auto& p : presets) p += "-wind";
        c["presets"] = presets;
        c["conversion"] = "logistic:0.2";
        c["map_age"] = 2;
        c["runs"] = quick ? 1 : 3;
        if (visual_) c["odometry"] = "visual: ORB + RANSAC similarity frame to frame at the filter rate, phase-correlation fallback";
        return c;
    }
    std::vector<Json> jobs(const Json& c) const override { return preset_run_jobs(c); }
    Json run_job(const Json& c, const Json& p, JobContext& ctx) const override {
        return fly(c, p.at("preset"), c.at("conversion"), c.at("map_age"), p.at("run"), ctx, ctx.plots && p.at("run") == 0, visual_);
    }
    std::string inputs_key(const Json& p) const override { return p.at("preset"); }  // one map age for the whole study
    std::string merge(const std::vector<Json>& o, const MergeContext& mc) const override {
        Table t;
        t.title = std::string("Figs 3.8-3.9: DPC-PFL (logistic:0.2) vs ") +
                  (visual_ ? "our image-based visual odometry (which also feeds the filter)" : "visual odometry (simulated drift)") +
                  "; ratios = odometry / filter (diss.: final error 2x, slope 11x)";
        t.header = {"Flight", "Distance km", "Final error filter m", "Final error odometry m", "Final ratio (ours)", "(diss.)",
                    "Slope filter m/km", "Slope odometry m/km", "Slope ratio (ours)", "(diss.)",
                    "Mean error filter m", "Mean error odometry m", "Lock lost events"};
        double final_ratio = 0, slope_ratio = 0;
        int n = 0;
        for (const Json& out : o) {
            const Json& r = out.at("result");
            const double ff = get(r, "filter_final_error_m"), of = get(r, "odometry_final_error_m");
            const double fs = get(r, "filter_error_slope_m_per_km"), os = get(r, "odometry_error_slope_m_per_km");
            // Job files from before issue 12 have no lock counters: "-" rather than a made-up 0.
            const std::string lost = r.contains("lock_lost_events") ? fmt(get(r, "lock_lost_events"), 0) : "-";
            t.rows.push_back({out.at("params").at("id").get<std::string>(), fmt(get(r, "distance_m") / 1000), fmt(ff), fmt(of), fmt(of / ff),
                              "2", fmt(fs), fmt(os), fmt(os / fs), "11", fmt(get(r, "filter_mean_error_m")),
                              fmt(get(r, "odometry_mean_error_m")), lost});
            final_ratio += of / ff, slope_ratio += os / fs, ++n;
        }
        t.rows.push_back({"Mean", "", "", "", fmt(final_ratio / n), "2", "", "", fmt(slope_ratio / n), "11", "", "", ""});
        t.write(mc.out, "table_odometry");
        const Table summary = odometry_summary(o, name());
        summary.write(mc.out, "table_odometry_summary");
        const Table broken = odometry_break_summary(o, name());
        broken.write(mc.out, "table_odometry_break");
        std::string md = summary.markdown() + "\n" + broken.markdown() + "\n" + t.markdown();
        if (visual_) md += "\n" + table_3_13([&](const std::string& p, const char* key) { return mean_of(o, key, FlightCell{p, ""}); }, mc.out);
        if (mc.plots) md += "\nPer-flight plots (trajectory.png, error.png) of run 0 are in " + mc.out + "/jobs/<flight>/\n";
        return md;
    }

private:
    bool wind_, visual_;
};

}  // namespace

std::unique_ptr<Study> make_conversion_study() { return std::make_unique<ConversionStudy>(); }
std::unique_ptr<Study> make_robustness_study() { return std::make_unique<RobustnessStudy>(); }
std::unique_ptr<Study> make_odometry_study(bool wind, bool visual) { return std::make_unique<OdometryStudy>(wind, visual); }

}  // namespace trn::experiments
