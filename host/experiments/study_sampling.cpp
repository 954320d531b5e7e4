// `sampling` [dissertation 3.4, Table 3.6]: rejection vs importance vs KLD sampling. As in the
// dissertation: a lost GPS fix, particles spread over a 312 m radius around the last known position,
// a straight ~1 km flight in 50 filter iterations, a 400x400 90-degree camera at 100 m; success =
// the best particle ends within 15 m of the truth. Every method sees the same start conditions
// (same start, direction, frames and sensor noise per start index).
#include <chrono>
#include <cmath>

#include "flight_outputs.hpp"  // quantile: the one median of the tables
#include "study.hpp"
#include "table.hpp"
#include "trn/localize/localizer.hpp"
#include "world.hpp"
#include "trn/detail/angles.hpp"

namespace trn::experiments {
namespace {

const char* kMethods[3] = {"rejection", "importance", "kld"};
const char* kPublished[3][3] = {{"500", "215", "90 %"}, {"500", "219", "99 %"}, {"150", "81.8", "94 %"}};

class SamplingStudy : public Study {
public:
    std::string name() const override { return "sampling"; }
    Json config(bool quick) const override {
        return {{"starts", quick ? 4 : 100}, {"iterations", 50}, {"flight_m", 1000},
                {"search_radius_m", 312},    {"success_m", 15},              {"particles", 500},
                {"altitude_m", 100},         {"camera", "400x400 90deg"},    {"template_width", 100},
                {"map", "procedural forest 2400 m, 1 m/px, map 2008 / frames 2010"},
                {"filter", "defaults (logistic:0.2, KLD eps 0.05 q 0.9, 5 m bins); initial set = fixed count = 500"}};
    }
    std::vector<Json> jobs(const Json& c) const override {
        std::vector<Json> out;
        for (int s = 0; s < c.at("starts").get<int>(); ++s)
            for (const char* m : kMethods) out.push_back({{"id", std::string(m) + "-" + std::to_string(s)}, {"method", m}, {"start", s}});
        return out;
    }

    std::string inputs_key(const Json&) const override { return "forest"; }  // every job: the same 2008 map, 2010 world
    Json run_job(const Json& c, const Json& p, JobContext& ctx) const override {
        const int start = p.at("start");
        const double size_m = 2400;
        const auto map = procedural_map(sim::TerrainStyle::Forest, ctx.seed, 2008, size_m);
        const auto world = procedural_map(sim::TerrainStyle::Forest, ctx.seed, 2010, size_m);
        const double mpp = map->metres_per_pixel;
        sim::Camera camera;
        camera.width = camera.height = 400;
        camera.hfov_deg = 90;
        const double altitude = c.at("altitude_m"), scale = sim::template_scale(camera, altitude, mpp);
        const int iterations = c.at("iterations");
        const double flight_m = c.at("flight_m"), step_m = flight_m / iterations;

        // Start conditions depend only on the start index (identical for every method).
        Rng rng(mix_seed(ctx.seed, 5000 + start));
        const double heading = rng.uniform(-kPi, kPi);
        const double dx = std::sin(heading) / mpp, dy = -std::cos(heading) / mpp;  // per metre, map pixels
        const double cx = size_m / 2 / mpp + rng.uniform(-200, 200) / mpp, cy = size_m / 2 / mpp + rng.uniform(-200, 200) / mpp;
        double x = cx - dx * flight_m / 2, y = cy - dy * flight_m / 2;

        localize::LocalizerConfig lc;
        lc.scoring.template_width = c.at("template_width");
        filter::FilterConfig& fc = lc.filter;
        fc = study_filter(c);
        fc.metres_per_pixel = mpp;
        fc.sampling = filter::parse_sampling_method(p.at("method").get<std::string>());
        fc.fixed_particles = c.at("particles");
        // Ours caps KLD at the fixed count (also its initial set); the dissertation profile starts
        // from it and has no maximum but its safety cap.
        if (c.value("profile", std::string("ours")) == "dissertation")
            fc.initial_particles = c.at("particles");
        else
            fc.max_particles = c.at("particles");
        fc.init_radius_m = fc.reinit_radius_m = c.at("search_radius_m");
        fc.seed = mix_seed(ctx.seed, 6000 + start);
        lc.start_x = x, lc.start_y = y, lc.start_heading_rad = heading;
        localize::Localizer localizer(map->image.view(), mpp, ctx.backend, lc);

        const auto t0 = std::chrono::steady_clock::now();
        localize::Estimate report;
        double evaluated = 0;
        for (int it = 0; it < iterations; ++it) {
            x += dx * step_m;
            y += dy * step_m;
            // Odometry with 3% scale noise and 1 m jitter, magnetometer within about 1 degree.
            const double d = step_m * (1 + 0.03 * rng.normal());
            const double h_odo = heading + 0.01 * rng.normal();
            localize::Observation in;
            in.odometry_east_m = d * std::sin(h_odo) + rng.normal();
            in.odometry_north_m = d * std::cos(h_odo) + rng.normal();
            in.heading_rad = heading + (kPi / 180) * rng.normal();
            const GrayImage frame = render_at(*world, camera, x, y, heading, altitude, mix_seed(ctx.seed, 7000 + start * 1000 + it));
            in.frame = frame.view();
            in.map_px_per_camera_px = scale;
            report = localizer.step(in);
            evaluated += report.particles;
        }
        const double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
        const localize::Estimate& e = report;
        const double best_err = std::hypot(e.best_x - x, e.best_y - y) * mpp, mean_err = std::hypot(e.x - x, e.y - y) * mpp;
        return {{"end_particles", report.particles}, {"seconds", wall},     {"best_error_m", best_err},
                {"estimate_error_m", mean_err},     {"evaluated", evaluated}, {"success", best_err <= c.at("success_m").get<double>()},
                {"reinitialisations", localizer.counters().reinitialisations}};
    }

    std::string merge(const std::vector<Json>& outputs, const MergeContext& mc) const override {
        Table t;
        t.title = "Table 3.6: comparison of sampling algorithms (ours: " + std::to_string(mc.config.at("starts").get<int>()) + " starts, " +
                  std::to_string(mc.config.at("iterations").get<int>()) + " iterations, backend " + mc.config.at("backend").get<std::string>() + ")";
        t.header = {"Algorithm", "End particle count (ours)", "(diss.)", "Total duration s (ours)", "(diss., i5-4200M)",
                    "Successful localization (ours)", "(diss.)", "Median best-particle error m (ours)"};
        for (int m = 0; m < 3; ++m) {
            double particles = 0, seconds = 0, success = 0;
            std::vector<double> errors;
            for (const Json& o : outputs) {
                if (o.at("params").at("method") != kMethods[m]) continue;
                const Json& r = o.at("result");
                particles += r.at("end_particles").get<double>();
                seconds += r.at("seconds").get<double>();
                success += r.at("success").get<bool>();
                errors.push_back(r.at("best_error_m").get<double>());
            }
            const double n = errors.size();
            // The median as every table takes it (quantile: between the two middle values of an even
            // count); it took the upper middle value (1.0 m for rejection under the dissertation profile,
            // where the median is 0.93 m).
            const double median = quantile(errors, 0.5);
            t.rows.push_back({kMethods[m], fmt(particles / n, 1), kPublished[m][0], fmt(seconds, 1), kPublished[m][1],
                              percent(100 * success / n, 0), kPublished[m][2], fmt(median, 1)});
        }
        t.write(mc.out, "table_3_6");
        return t.markdown();
    }
};

}  // namespace

std::unique_ptr<Study> make_sampling_study() { return std::make_unique<SamplingStudy>(); }

}  // namespace trn::experiments
