// The studies made of whole simulated flights localized by DPC-PFL:
//   conversion [3.5, Tables 3.7-3.11]: scenario presets x conversion functions x seeds;
//   robustness [3.5.3, Table 3.12, Fig 3.7]: the parametric functions on maps 0, 2, 4, 6 years older
//     than the world the camera sees;
//   odometry   [3.6, Figs 3.8-3.9]: filter vs visual-odometry error, final-error and slope ratios;
//     odometry-visual: the same with the odometry computed from the frames (visual_odometry.hpp),
//     also Table 3.13 [3.7] on its four presets (table_3_13.cpp).
// One job = one flight (preset, conversion, map age, run index).
#include <cmath>
#include <filesystem>
#include <map>

#include "study.hpp"
#include "table.hpp"
#include "trn/filter/flight_source.hpp"
#include "trn/filter/localization.hpp"
#include "trn/filter/report.hpp"
#include "trn/filter/scorer.hpp"
#include "trn/filter/visual_odometry.hpp"
#include "table_3_13.hpp"
#include "world.hpp"

namespace trn::experiments {
namespace {

const std::vector<std::string> kAllPresets{"FL-200", "FL-300", "FR-200", "FR-300", "FC-200", "FC-300",
                                           "UL-200", "UL-300", "UR-200", "UR-300", "UC-200", "UC-300"};
const std::vector<std::string> kParametric{"rectifying:0.2", "rectifying:0.1", "rectifying:0",  "rectifying:-0.1", "rectifying:-0.2",
                                           "logistic:0.7",   "logistic:0.4",   "logistic:0.2", "logistic:0.1",    "logistic:0.05"};
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
            {"filter", "defaults: KLD (eps 0.05, q 0.9, 5 m bins, 100..2000), 300 m init radius, motion along the odometry's "
                       "displacement vector (alpha 0.05/0.03/0.2, eps 1 m/2 deg), lock monitor on (48 probes, contrast 3/5.5)"}};
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
    const std::size_t stride = std::max<std::size_t>(1, std::lround(preset.fps / c.at("rate_hz").get<double>()));
    filter::SimulatedFlightSource simulated(*world, fc, stride);
    filter::VisualOdometrySource visual(simulated, world->metres_per_pixel);
    filter::FlightSource& source = visual_odometry ? static_cast<filter::FlightSource&>(visual) : simulated;
    filter::BackendScorerOptions so;
    so.template_width = c.at("template_width");
    filter::BackendScorer scorer(ctx.backend, map->image.view(), so);
    filter::FilterConfig cfg;
    cfg.metres_per_pixel = map->metres_per_pixel;
    cfg.conversion = filter::Conversion::parse(conversion);
    cfg.seed = mix_seed(ctx.seed, 200 + run);
    filter::ParticleFilter pf(scorer, cfg);
    const filter::LocalizationResult r = filter::run_localization(source, pf);
    const filter::LocalizationSummary& s = r.summary;
    std::filesystem::create_directories(ctx.job_folder);
    filter::write_rows_csv(ctx.job_folder + "/localization.csv", r.rows);
    if (plots) filter::plot_run(ctx.job_folder, r.rows, s, map->image.view(), map->metres_per_pixel, preset_name + " " + conversion);
    auto num = [](double v) { return std::isfinite(v) ? Json(v) : Json(nullptr); };
    Json result = {{"filter_mean_error_m", num(s.filter_mean_error_m)},
            {"odometry_mean_error_m", num(s.odometry_mean_error_m)},
            {"filter_final_error_m", num(s.filter_final_error_m)},
            {"odometry_final_error_m", num(s.odometry_final_error_m)},
            {"filter_slope_m_per_km", num(s.filter_error_slope_m_per_km)},
            {"odometry_slope_m_per_km", num(s.odometry_error_slope_m_per_km)},
            {"steps", s.steps},
            {"distance_m", s.distance_m},
            {"mean_particles", s.mean_particles},
            {"particles_evaluated", s.mean_particles * s.steps},
            {"reinitialisations", s.counters.reinitialisations},
            {"lock_lost_events", s.counters.lock_lost_events},
            {"weak_contrast_steps", s.counters.weak_contrast_steps},
            {"odometry_inconsistent_steps", s.counters.odometry_inconsistent_steps}};
    if (visual_odometry)
        result["visual_odometry_steps"] = {{"features", visual.counts().features}, {"phase", visual.counts().phase}, {"lost", visual.counts().lost}};
    return result;
}

double get(const Json& j, const char* key) { return j.at(key).is_null() ? NAN : j.at(key).get<double>(); }

// Mean of `key` over the jobs matching preset / conversion / age (any when empty / -1).
double mean_of(const std::vector<Json>& outputs, const char* key, const std::string& preset, const std::string& conversion, int age = -1) {
    double sum = 0;
    int n = 0;
    for (const Json& o : outputs) {
        const Json& p = o.at("params");
        if ((!preset.empty() && p.at("preset") != preset) || (!conversion.empty() && p.at("conversion") != conversion) ||
            (age >= 0 && p.at("map_age") != age))
            continue;
        const double v = get(o.at("result"), key);
        if (std::isfinite(v)) sum += v, ++n;
    }
    return n ? sum / n : NAN;
}

std::vector<std::string> strings(const Json& j) { return j.get<std::vector<std::string>>(); }

// ------------------------------------------------------------------------------------------------
// Published numbers (Tables 3.7, 3.8, 3.10, 3.11), per preset in kAllPresets order.
const double kLogistic[12][5] = {{39.27, 37.41, 55.91, 225.41, 238.70}, {26.74, 26.09, 27.66, 25.63, 160.18}, {62.71, 52.73, 74.06, 62.36, 58.20},
                                 {64.34, 59.25, 31.83, 32.54, 58.48},   {57.32, 68.53, 92.39, 102.86, 49.36}, {95.63, 112.06, 126.93, 156.09, 140.20},
                                 {27.17, 27.64, 26.56, 25.46, 28.27},   {27.27, 25.88, 25.95, 26.60, 27.57},  {54.69, 42.43, 37.09, 66.53, 52.23},
                                 {50.00, 43.55, 41.27, 45.07, 55.10},   {70.42, 56.57, 49.09, 48.38, 65.56},  {73.71, 64.74, 54.29, 63.16, 67.49}};
const double kRectifying[12][5] = {{39.97, 37.66, 50.79, 145.09, 233.22}, {27.01, 25.74, 27.14, 56.05, 184.69}, {59.64, 67.15, 72.57, 72.03, 79.35},
                                   {59.50, 51.41, 40.72, 29.18, 35.53},   {58.26, 73.73, 78.47, 67.71, 26.03},  {92.44, 116.12, 125.66, 142.34, 112.88},
                                   {29.81, 27.40, 26.67, 27.03, 26.61},   {26.66, 26.34, 25.01, 25.60, 25.27},  {58.50, 44.85, 36.39, 42.53, 49.48},
                                   {53.54, 42.82, 39.55, 39.92, 42.68},   {78.07, 72.78, 49.43, 50.33, 48.05},  {76.03, 67.38, 57.79, 56.38, 61.53}};
const double kImprovement[12][3] = {{7.79, 15.59, 7.24},   {6.47, 32.40, 24.35},  {14.77, 10.18, -4.00}, {6.37, 85.07, 73.99},
                                    {2.48, -40.14, -41.59}, {-2.58, -23.61, -21.58}, {12.10, 65.12, 47.30}, {12.37, 48.47, 32.12},
                                    {22.90, 224.89, 164.34}, {6.49, 98.27, 86.19}, {0.81, 95.25, 93.67},  {2.79, 63.48, 59.04}};
const double kSpeedup[12][3] = {{1.06, 2.41, 2.26}, {1.07, 2.32, 2.17}, {1.11, 3.23, 2.92}, {1.14, 3.36, 2.95}, {1.00, 2.66, 2.65}, {0.99, 2.51, 2.53},
                                {1.14, 3.76, 3.31}, {1.12, 3.40, 3.03}, {1.14, 3.66, 3.21}, {1.10, 3.37, 3.07}, {1.01, 3.62, 3.58}, {1.02, 3.89, 3.83}};
const int kRankScore[10] = {75, 54, 56, 69, 88, 82, 68, 52, 58, 58};
const char* kRank[10] = {"8", "2", "3", "7", "10", "9", "6", "1", "4-5", "4-5"};
const double kRobust[10][3] = {{3.14, 54.16, 5.8}, {4.09, 52.36, 7.8}, {4.14, 53.64, 7.7}, {26.06, 73.73, 35.4}, {42.09, 86.80, 48.5},
                               {3.20, 54.95, 5.8}, {4.29, 54.45, 7.9}, {8.96, 53.08, 16.9}, {28.99, 62.85, 46.1}, {44.49, 77.11, 57.7}};

int preset_index(const std::string& p) { return static_cast<int>(std::find(kAllPresets.begin(), kAllPresets.end(), p) - kAllPresets.begin()); }

class ConversionStudy : public Study {
public:
    std::string name() const override { return "conversion"; }
    Json config(bool quick) const override {
        Json c = flight_config(quick);
        c["presets"] = quick ? std::vector<std::string>{"UR-200"} : kAllPresets;
        std::vector<std::string> f{"linear", "softmax"};
        f.insert(f.end(), kParametric.begin(), kParametric.end());
        c["conversions"] = f;
        c["runs"] = quick ? 1 : 10;
        c["map_age"] = 2;
        return c;
    }
    std::vector<Json> jobs(const Json& c) const override {
        std::vector<Json> out;
        for (const auto& p : strings(c.at("presets")))
            for (const auto& f : strings(c.at("conversions")))
                for (int r = 0; r < c.at("runs").get<int>(); ++r)
                    out.push_back({{"id", p + "-" + safe_id(f) + "-" + std::to_string(r)}, {"preset", p}, {"conversion", f}, {"map_age", c.at("map_age")}, {"run", r}});
        return out;
    }
    Json run_job(const Json& c, const Json& p, JobContext& ctx) const override {
        return fly(c, p.at("preset"), p.at("conversion"), p.at("map_age"), p.at("run"), ctx, false);
    }
    std::string merge(const std::vector<Json>& o, const MergeContext& mc) const override {
        const auto presets = strings(mc.config.at("presets"));
        const std::string runs = std::to_string(mc.config.at("runs").get<int>());
        std::string md;
        for (int fam = 0; fam < 2; ++fam) {
            Table t;
            t.title = std::string("Table 3.") + (fam ? "8" : "7") + ": mean localization error (m), " + (fam ? "rectifying" : "logistic") +
                      " conversion, mean of " + runs + " runs per cell (ours | diss.)";
            t.header = {"Scenario"};
            for (int k = 0; k < 5; ++k) {
                const std::string f = kParametric[(fam ? 0 : 5) + k];
                t.header.push_back(f + " (ours)");
                t.header.push_back("(diss.)");
            }
            for (const auto& p : presets) {
                std::vector<std::string> row{p};
                for (int k = 0; k < 5; ++k) {
                    row.push_back(fmt(mean_of(o, "filter_mean_error_m", p, kParametric[(fam ? 0 : 5) + k])));
                    row.push_back(fmt((fam ? kRectifying : kLogistic)[preset_index(p)][k]));
                }
                t.rows.push_back(row);
            }
            t.write(mc.out, fam ? "table_3_8" : "table_3_7");
            md += t.markdown() + "\n";
        }
        // Table 3.9: rank the ten parametric functions within each scenario (1 = most accurate).
        std::vector<double> score(10, 0);
        for (const auto& p : presets) {
            std::vector<std::pair<double, int>> acc;
            for (int k = 0; k < 10; ++k) acc.push_back({mean_of(o, "filter_mean_error_m", p, kParametric[k]), k});
            std::sort(acc.begin(), acc.end());
            for (int r = 0; r < 10; ++r) score[acc[r].second] += r + 1;
        }
        std::vector<int> order(10);
        for (int k = 0; k < 10; ++k) order[k] = k;
        std::stable_sort(order.begin(), order.end(), [&](int a, int b) { return score[a] < score[b]; });
        Table r;
        r.title = "Table 3.9: conversion function ranking by accuracy (sum of per-scenario ranks over " + std::to_string(presets.size()) +
                  " scenario(s); the dissertation sums over 12)";
        r.header = {"Function", "Score (ours)", "Rank (ours)", "Score (diss.)", "Rank (diss.)"};
        for (int k = 0; k < 10; ++k) {
            const int rank = static_cast<int>(std::find(order.begin(), order.end(), k) - order.begin()) + 1;
            r.rows.push_back({kParametric[k], fmt(score[k], 0), std::to_string(rank), std::to_string(kRankScore[k]), kRank[k]});
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
            std::vector<double> sum(3, 0), pub(3, 0);
            int n = 0;
            for (const auto& p : presets) {
                const double lin = mean_of(o, key, p, "linear"), soft = mean_of(o, key, p, "softmax"), logi = mean_of(o, key, p, "logistic:0.2");
                const double v[3] = {which ? lin / soft : (lin / soft - 1) * 100, which ? lin / logi : (lin / logi - 1) * 100,
                                     which ? soft / logi : (soft / logi - 1) * 100};
                std::vector<std::string> row{p};
                for (int k = 0; k < 3; ++k) {
                    const double published = (which ? kSpeedup : kImprovement)[preset_index(p)][k];
                    row.push_back(which ? fmt(v[k]) : percent(v[k]));
                    row.push_back(which ? fmt(published) : percent(published));
                    sum[k] += v[k], pub[k] += published;
                }
                ++n;
                t.rows.push_back(row);
            }
            std::vector<std::string> avg{"Average"};
            for (int k = 0; k < 3; ++k) {
                avg.push_back(which ? fmt(sum[k] / n) : percent(sum[k] / n));
                avg.push_back(which ? fmt(pub[k] / n) : percent(pub[k] / n));
            }
            t.rows.push_back(avg);
            t.write(mc.out, which ? "table_3_11" : "table_3_10");
            md += t.markdown() + "\n";
        }
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
    std::vector<Json> jobs(const Json& c) const override {
        std::vector<Json> out;
        for (const auto& p : strings(c.at("presets")))
            for (const auto& f : strings(c.at("conversions")))
                for (int age : c.at("map_ages").get<std::vector<int>>())
                    for (int r = 0; r < c.at("runs").get<int>(); ++r)
                        out.push_back({{"id", p + "-" + safe_id(f) + "-age" + std::to_string(age) + "-" + std::to_string(r)},
                                       {"preset", p}, {"conversion", f}, {"map_age", age}, {"run", r}});
        return out;
    }
    Json run_job(const Json& c, const Json& p, JobContext& ctx) const override {
        return fly(c, p.at("preset"), p.at("conversion"), p.at("map_age"), p.at("run"), ctx, false);
    }
    std::string merge(const std::vector<Json>& o, const MergeContext& mc) const override {
        const auto ages = mc.config.at("map_ages").get<std::vector<int>>();
        Table t;
        t.title = "Table 3.12: localization error over maps 0/2/4/6 years older than the flight (SD over the map ages of the mean error)";
        t.header = {"Function", "SD m (ours)", "(diss.)", "Mean error m (ours)", "(diss.)", "RSD (ours)", "(diss.)"};
        std::vector<std::vector<double>> cols{{}};
        for (int a : ages) cols[0].push_back(kFlightYear + a);
        std::vector<std::string> titles;
        for (const auto& f : strings(mc.config.at("conversions"))) {
            std::vector<double> per_age;
            for (int a : ages) per_age.push_back(mean_of(o, "filter_mean_error_m", "", f, a));
            double mean = 0, var = 0;
            for (double v : per_age) mean += v / per_age.size();
            for (double v : per_age) var += (v - mean) * (v - mean) / (per_age.size() - 1);
            const double sd = std::sqrt(var);
            const int k = static_cast<int>(std::find(kParametric.begin(), kParametric.end(), f) - kParametric.begin());
            t.rows.push_back({f, fmt(sd), k < 10 ? fmt(kRobust[k][0]) : "-", fmt(mean), k < 10 ? fmt(kRobust[k][1]) : "-",
                              percent(100 * sd / mean, 1), k < 10 ? percent(kRobust[k][2], 1) : "-"});
            cols.push_back(per_age);
            titles.push_back(f);
        }
        t.write(mc.out, "table_3_12");
        if (mc.plots)
            line_plot(mc.out + "/fig_3_7.png", "Fig 3.7: mean localization error vs map year (flight imagery 2008)", "map year",
                      "mean error (m)", cols, titles, {.x_tic_step = 2, .vertical_lines = {}});
        return t.markdown();
    }
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
    std::vector<Json> jobs(const Json& c) const override {
        std::vector<Json> out;
        for (const auto& p : strings(c.at("presets")))
            for (int r = 0; r < c.at("runs").get<int>(); ++r) out.push_back({{"id", p + "-" + std::to_string(r)}, {"preset", p}, {"run", r}});
        return out;
    }
    Json run_job(const Json& c, const Json& p, JobContext& ctx) const override {
        return fly(c, p.at("preset"), c.at("conversion"), c.at("map_age"), p.at("run"), ctx, ctx.plots && p.at("run") == 0, visual_);
    }
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
            const double fs = get(r, "filter_slope_m_per_km"), os = get(r, "odometry_slope_m_per_km");
            // Job files from before issue 12 have no lock counters: "-" rather than a made-up 0.
            const std::string lost = r.contains("lock_lost_events") ? fmt(get(r, "lock_lost_events"), 0) : "-";
            t.rows.push_back({out.at("params").at("id").get<std::string>(), fmt(get(r, "distance_m") / 1000), fmt(ff), fmt(of), fmt(of / ff),
                              "2", fmt(fs), fmt(os), fmt(os / fs), "11", fmt(get(r, "filter_mean_error_m")),
                              fmt(get(r, "odometry_mean_error_m")), lost});
            final_ratio += of / ff, slope_ratio += os / fs, ++n;
        }
        t.rows.push_back({"Mean", "", "", "", fmt(final_ratio / n), "2", "", "", fmt(slope_ratio / n), "11", "", "", ""});
        t.write(mc.out, "table_odometry");
        std::string md = t.markdown();
        if (visual_) md += "\n" + table_3_13([&](const std::string& p, const char* key) { return mean_of(o, key, p, ""); }, mc.out);
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
