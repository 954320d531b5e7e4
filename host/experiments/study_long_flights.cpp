// Two flight studies of issue 17 that the dissertation's setup asks for and the other flight
// studies (study_flights.cpp) do not cover:
//   odometry-long  [Table 2.2, Figs 3.8-3.9]: the twelve "-long" presets, each flown whole at the
//     dissertation's distance (0.97-4.75 km) with climbs and descents between 200 and 300 m,
//     filter vs odometry;
//   template-width: the same flights scored with templates downscaled to 160 px and at the
//     camera's full 640 px, so the cost/accuracy trade-off of the downscaling is measured.
// One job = one flight. Settings otherwise as the odometry study: 2 Hz, logistic:0.2, map 2 years
// newer than the world the camera sees, the filter's defaults.
#include <algorithm>
#include <cmath>
#include <filesystem>

#include "flight_outputs.hpp"
#include "flight_settings.hpp"
#include "study.hpp"
#include "table.hpp"
#include "trn/localize/localization.hpp"
#include "trn/localize/report.hpp"
#include "world.hpp"
#include "trn/detail/json_number.hpp"

namespace trn::experiments {
namespace {

constexpr int kFlightYear = 2008;

// The settings both studies share (the filter named as in study_flights.cpp: flight_settings.hpp).
Json shared_config() {
    return {{"rate_hz", 2},
            {"flight_year", kFlightYear},
            {"map_age", 2},
            {"conversion", "logistic:0.2"},
            {"filter", kFilterDefaults},
            {"init_radius_m", filter::FilterConfig{}.init_radius_m}};  // trnkit experiment --init-radius-m
}

std::string width_name(int w) { return w == 0 ? "full" : std::to_string(w); }

// Flies `preset` for distance_m (0: its whole flight) with templates `template_width` px wide
// (0: full resolution) and localizes it; the map is sized by sim::fitting_map_edge_m.
Json fly(const Json& c, const std::string& preset_name, double distance_m, int template_width, int run, JobContext& ctx) {
    const sim::Scenario& preset = sim::find_scenario(preset_name);
    sim::FlightConfig fc;
    fc.scenario = preset;
    fc.seed = mix_seed(ctx.seed, 100 + run);
    fc.frames = distance_m > 0 ? static_cast<std::size_t>(std::llround(distance_m / preset.speed_mps * preset.fps)) : 0;
    const double size_m = sim::fitting_map_edge_m(fc);
    const int map_age = c.at("map_age");
    const auto world = procedural_map(preset.terrain, ctx.seed, kFlightYear, size_m);
    const auto map = procedural_map(preset.terrain, ctx.seed, kFlightYear + map_age, size_m);

    // The altitudes actually flown (truth only, no rendering: well under a second).
    double alt_min = 1e300, alt_max = 0;
    {
        sim::FlightConfig truth_only = fc;
        truth_only.render_images = false;
        sim::FlightSimulator sim(*world, truth_only);
        sim::FlightFrame f;
        while (sim.next(f)) alt_min = std::min(alt_min, f.truth.altitude_m), alt_max = std::max(alt_max, f.truth.altitude_m);
    }

    localize::LocalizationSpec spec;
    spec.flight = localize::SimulatedFlight{world.get(), fc};
    spec.rate_hz = c.at("rate_hz").get<double>();
    spec.localizer.scoring.template_width = template_width;
    filter::FilterConfig& cfg = spec.localizer.filter;
    cfg = study_filter(c);
    cfg.metres_per_pixel = map->metres_per_pixel;
    cfg.conversion = filter::Conversion::parse(c.at("conversion").get<std::string>());
    cfg.init_radius_m = c.at("init_radius_m");
    cfg.seed = mix_seed(ctx.seed, 200 + run);
    const localize::LocalizationResult r = localize::run_localization(spec, map->image.view(), map->metres_per_pixel, ctx.backend);
    const localize::LocalizationSummary& s = r.summary;
    std::filesystem::create_directories(ctx.job_folder);
    localize::write_rows_csv(ctx.job_folder + "/localization.csv", r.rows);
    if (ctx.plots) localize::plot_run(ctx.job_folder, r.rows, s, map->image.view(), map->metres_per_pixel, preset_name);
    const auto num = json_number<Json>;
    Json result = flight_result(s);
    result["altitude_min_m"] = alt_min;
    result["altitude_max_m"] = alt_max;
    result["map_edge_m"] = size_m;
    // Filter time per step (sampling + scoring + estimate; not rendering) and scoring alone.
    result["filter_ms_per_step"] = num(s.frames_per_second > 0 ? 1000 / s.frames_per_second : NAN);
    result["score_ms_per_step"] = num(s.mean_score_ms);
    return result;
}

std::vector<std::string> strings(const Json& j) { return j.get<std::vector<std::string>>(); }

std::vector<std::string> long_presets() {
    std::vector<std::string> out;
    for (const sim::Scenario& s : sim::scenario_presets())
        if (s.one_loop) out.push_back(s.name);
    return out;
}

class LongOdometryStudy : public Study {
public:
    std::string name() const override { return "odometry-long"; }
    Json config(bool quick) const override {
        Json c = shared_config();
        c["presets"] = quick ? std::vector<std::string>{"FC-300-long"} : long_presets();
        c["distance_m"] = 0;  // each preset's whole flight (Table 2.2); quick: the shortest, at 1 Hz
        if (quick) c["rate_hz"] = 1;
        c["template_width"] = quick ? 96 : 160;
        c["runs"] = 1;
        return c;
    }
    std::vector<Json> jobs(const Json& c) const override { return preset_run_jobs(c); }
    Json run_job(const Json& c, const Json& p, JobContext& ctx) const override {
        return fly(c, p.at("preset"), c.at("distance_m"), c.at("template_width"), p.at("run"), ctx);
    }
    std::string merge(const std::vector<Json>& o, const MergeContext& mc) const override {
        Table t;
        t.title = "Flights of the dissertation's lengths (Table 2.2), 200 <-> 300 m: DPC-PFL (logistic:0.2) vs odometry; "
                  "ratios = odometry / filter (diss.: final error 2x, slope 11x)";
        t.header = {"Flight", "Distance km", "Altitude m", "Final error filter m", "Final error odometry m", "Final ratio", "Slope filter m/km",
                    "Slope odometry m/km", "Mean error filter m", "Mean error odometry m", "Lock lost events", "Job wall s"};
        for (const Json& out : o) {
            const Json& r = out.at("result");
            const double ff = get(r, "filter_final_error_m"), of = get(r, "odometry_final_error_m");
            t.rows.push_back({out.at("params").at("id").get<std::string>(), fmt(get(r, "distance_m") / 1000),
                              fmt(get(r, "altitude_min_m"), 0) + "-" + fmt(get(r, "altitude_max_m"), 0), fmt(ff), fmt(of), fmt(of / ff),
                              fmt(get(r, "filter_error_slope_m_per_km")), fmt(get(r, "odometry_error_slope_m_per_km")), fmt(get(r, "filter_mean_error_m")),
                              fmt(get(r, "odometry_mean_error_m")), fmt(get(r, "lock_lost_events"), 0), fmt(out.value("wall_s", NAN), 0)});
        }
        t.write(mc.out, "table_long_flights");
        const Table summary = odometry_summary(o, name());
        summary.write(mc.out, "table_odometry_summary");
        return summary.markdown() + "\n" + t.markdown();
    }
};

class TemplateWidthStudy : public Study {
public:
    std::string name() const override { return "template-width"; }
    Json config(bool quick) const override {
        Json c = shared_config();
        c["presets"] = quick ? std::vector<std::string>{"UC-300"} : std::vector<std::string>{"FL-200", "UR-200", "FC-300"};
        c["distance_m"] = quick ? 12 : 1000;  // quick: 3 steps (a full-resolution step costs seconds)
        c["template_widths"] = quick ? std::vector<int>{48, 0} : std::vector<int>{160, 0};  // 0: full resolution (640 px)
        c["runs"] = 1;
        return c;
    }
    std::vector<Json> jobs(const Json& c) const override {
        std::vector<Json> out;
        for (const auto& p : strings(c.at("presets")))
            for (int w : c.at("template_widths").get<std::vector<int>>())
                for (int r = 0; r < c.at("runs").get<int>(); ++r)
                    out.push_back({{"id", p + "-w" + width_name(w) + "-" + std::to_string(r)}, {"preset", p}, {"template_width", w}, {"run", r}});
        return out;
    }
    Json run_job(const Json& c, const Json& p, JobContext& ctx) const override {
        return fly(c, p.at("preset"), c.at("distance_m"), p.at("template_width"), p.at("run"), ctx);
    }
    // The map is sized to the flight (its seed is the run's), so only the widths of one run share it.
    std::string inputs_key(const Json& p) const override { return p.at("preset").get<std::string>() + "-" + std::to_string(p.at("run").get<int>()); }
    std::string merge(const std::vector<Json>& o, const MergeContext& mc) const override {
        Table t;
        t.title = "Template width: the same flights scored with downscaled and full-resolution (640 px) templates";
        t.header = {"Flight", "Template px", "Mean error filter m", "Final error filter m", "Mean error odometry m", "Mean particles",
                    "Filter ms/step", "Scoring ms/step", "Job wall s", "Steps"};
        for (const Json& out : o) {
            const Json& r = out.at("result");
            const Json& p = out.at("params");
            t.rows.push_back({p.at("preset").get<std::string>() + "-" + std::to_string(p.at("run").get<int>()), width_name(p.at("template_width")),
                              fmt(get(r, "filter_mean_error_m")), fmt(get(r, "filter_final_error_m")), fmt(get(r, "odometry_mean_error_m")),
                              fmt(get(r, "mean_particles"), 0), fmt(get(r, "filter_ms_per_step"), 1), fmt(get(r, "score_ms_per_step"), 1),
                              fmt(out.value("wall_s", NAN), 1), fmt(get(r, "steps"), 0)});
        }
        t.write(mc.out, "table_template_width");
        return t.markdown();
    }
};

}  // namespace

std::unique_ptr<Study> make_long_odometry_study() { return std::make_unique<LongOdometryStudy>(); }
std::unique_ptr<Study> make_template_width_study() { return std::make_unique<TemplateWidthStudy>(); }

}  // namespace trn::experiments
