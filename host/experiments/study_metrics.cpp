// `metrics` [dissertation 3.2, Table 3.4, Fig 3.4]: NCC vs CC vs SSD on 500 pose hypotheses around
// a ground truth, with the camera frame corrupted by 5%/5% salt-and-pepper and Gaussian noise
// (mean 25, sigma 40). All three measures come from one Backend::score call per trial. The top-5
// analysis takes the 5 hypotheses nearest the truth: N+ = how many of them score >= a threshold
// (their min / mean / max), N- = how many of the other 495 do; accuracy = N+ / (N- + N+).
#include <algorithm>
#include <cmath>
#include <filesystem>
#include <numeric>

#include "study.hpp"
#include "table.hpp"
#include "trn/filter/scorer.hpp"
#include "world.hpp"
#include "trn/detail/angles.hpp"

namespace trn::experiments {
namespace {

const char* kMeasures[3] = {"ncc", "cc", "ssd"};
// Table 3.4 as published (NCC, CC, SSD per row).
const char* kPublished[12][3] = {
    {"0.0122", "0.7185", "0"},     {"0.0550", "0.7471", "0.0000"}, {"0.1253", "0.7703", "0.0000"}, {"5", "5", "5"},
    {"2", "2", "5"},               {"1", "1", "5"},                {"166", "151", "141"},          {"31", "74", "141"},
    {"3", "15", "141"},            {"2.92%", "3.21%", "3.42%"},    {"6.45%", "2.70%", "3.42%"},    {"25.00%", "6.25%", "3.42%"}};
const char* kRowNames[12] = {"Top 5 Min", "Top 5 Average", "Top 5 Max", "Top 5 particles above Min (N+)",
                             "Top 5 particles above Average (N+)", "Top 5 particles above Max (N+)", "Particles Above Top 5 Min (N-)",
                             "Particles Above Top 5 Average (N-)", "Particles Above Top 5 Max (N-)", "Top 5 Min Accuracy",
                             "Top 5 Average Accuracy", "Top 5 Max Accuracy"};

float measure(const ParticleScore& s, int m) { return m == 0 ? s.ncc : m == 1 ? s.cc : s.ssd; }

class MetricsStudy : public Study {
public:
    explicit MetricsStudy(std::string orthophoto) : orthophoto_(std::move(orthophoto)) {}
    std::string name() const override { return "metrics"; }
    Json config(bool quick) const override {
        return {{"hypotheses", 500},       {"radius_m", 100},        {"trials_per_map", quick ? 3 : 20},
                {"altitude_m", 200},       {"camera", "640x480 60deg"}, {"template_width", 160},
                {"procedural_map", "forest 1200 m, 1 m/px, map 2008 / frames 2010"},
                {"orthophoto", orthophoto_.empty() ? "absent" : "present (0.5 m/px, frames from the map aged 2 years)"},
                {"noise", "salt 5%, pepper 5%, gaussian mean 25 sigma 40"}};
    }
    std::vector<Json> jobs(const Json& c) const override {
        std::vector<Json> out;
        std::vector<std::string> maps{"procedural"};
        if (c.at("orthophoto") != "absent") maps.push_back("orthophoto");
        for (const auto& m : maps)
            for (int t = 0; t < c.at("trials_per_map").get<int>(); ++t) out.push_back({{"id", m + "-" + std::to_string(t)}, {"map", m}, {"trial", t}});
        return out;
    }

    std::string inputs_key(const Json& p) const override { return p.at("map"); }  // the map pair of study_map_pair
    Json run_job(const Json& c, const Json& p, JobContext& ctx) const override {
        const bool ortho = p.at("map") == "orthophoto";
        const int trial = p.at("trial");
        const auto [map, world] = study_map_pair(ortho ? orthophoto_ : std::string(), ctx.seed);
        const double mpp = map->metres_per_pixel, altitude = c.at("altitude_m"), radius_px = c.at("radius_m").get<double>() / mpp;
        const sim::Camera camera;
        const double scale = sim::template_scale(camera, altitude, mpp);
        const double half_diag = 0.5 * std::hypot(camera.width, camera.height) * scale;
        Rng rng(mix_seed(ctx.seed, 1000 + trial + (ortho ? 500000 : 0)));
        const double margin = half_diag + radius_px + 2;
        if (map->image.width < 2 * margin || map->image.height < 2 * margin) throw Error("metrics: map too small for the footprint");
        const double tx = rng.uniform(margin, map->image.width - margin), ty = rng.uniform(margin, map->image.height - margin);
        const double tyaw = rng.uniform(-kPi, kPi);
        GrayImage frame = render_at(*world, camera, tx, ty, tyaw, altitude, mix_seed(ctx.seed, 77 + trial));
        add_dissertation_noise(frame, mix_seed(ctx.seed, 99 + trial));

        // Hypotheses uniform in the disc (heading known, as with a magnetometer).
        const int n = c.at("hypotheses");
        std::vector<Pose> poses(n);
        std::vector<double> dist_m(n);
        for (int i = 0; i < n; ++i) {
            const double r = radius_px * std::sqrt(rng.uniform()), a = rng.uniform(0, 2 * kPi);
            poses[i] = {static_cast<float>(tx + r * std::cos(a)), static_cast<float>(ty + r * std::sin(a)), static_cast<float>(tyaw), 1};
            dist_m[i] = r * mpp;
        }
        filter::BackendScorerOptions so;
        so.template_width = c.at("template_width");
        filter::BackendScorer scorer(ctx.backend, map->image.view(), so);
        std::vector<ParticleScore> scores(n);
        scorer.score(frame.view(), scale, poses, scores, nullptr);  // one Backend::score call: ncc, cc, ssd

        std::vector<int> order(n);
        std::iota(order.begin(), order.end(), 0);
        std::sort(order.begin(), order.end(), [&](int a, int b) { return dist_m[a] < dist_m[b]; });
        std::vector<bool> top(n, false);
        for (int k = 0; k < 5; ++k) top[order[k]] = true;
        Json result{{"truth", {tx, ty, tyaw}}, {"invalid", 0}};
        int invalid = 0;
        for (const auto& s : scores) invalid += !s.valid();
        result["invalid"] = invalid;
        for (int m = 0; m < 3; ++m) {
            double mn = 1e300, mx = -1e300, sum = 0;
            for (int k = 0; k < 5; ++k) {
                const double v = measure(scores[order[k]], m);
                mn = std::min(mn, v), mx = std::max(mx, v), sum += v;
            }
            const double thresholds[3] = {mn, sum / 5, mx};
            Json mj{{"top5_min", mn}, {"top5_avg", sum / 5}, {"top5_max", mx}};
            const char* keys[3] = {"min", "avg", "max"};
            for (int t = 0; t < 3; ++t) {
                int plus = 0, minus = 0;
                for (int i = 0; i < n; ++i)
                    if (measure(scores[i], m) >= thresholds[t]) (top[i] ? plus : minus)++;
                mj[std::string("n_plus_") + keys[t]] = plus;
                mj[std::string("n_minus_") + keys[t]] = minus;
                mj[std::string("accuracy_") + keys[t]] = 100.0 * plus / (plus + minus);
            }
            // Where the best-scoring hypothesis is: how far from the truth.
            int best = 0;
            for (int i = 1; i < n; ++i)
                if (measure(scores[i], m) > measure(scores[best], m)) best = i;
            mj["best_distance_m"] = dist_m[best];
            result[kMeasures[m]] = mj;
        }
        if (trial == 0) {  // the hypothesis plot of Fig 3.4 needs one trial's scores
            Json series = Json::array();
            for (int i = 0; i < n; ++i) series.push_back({dist_m[i], scores[i].ncc, scores[i].cc, scores[i].ssd});
            result["series"] = series;
        }
        return result;
    }

    std::string merge(const std::vector<Json>& outputs, const MergeContext& mc) const override {
        std::string md;
        for (const std::string map : {"procedural", "orthophoto"}) {
            std::vector<const Json*> rs;
            for (const Json& o : outputs)
                if (o.at("params").at("map") == map) rs.push_back(&o.at("result"));
            if (rs.empty()) continue;
            auto mean = [&](int m, const std::string& key) {
                double s = 0;
                for (const Json* r : rs) s += r->at(kMeasures[m]).at(key).get<double>();
                return s / rs.size();
            };
            const char* keys[12] = {"top5_min", "top5_avg", "top5_max", "n_plus_min", "n_plus_avg", "n_plus_max", "n_minus_min",
                                    "n_minus_avg", "n_minus_max", "accuracy_min", "accuracy_avg", "accuracy_max"};
            Table t;
            t.title = "Table 3.4 (" + map + " map): similarity metric comparison, mean of " + std::to_string(rs.size()) +
                      " trials of 500 hypotheses (ours) vs the dissertation (one trial)";
            t.header = {"Value", "NCC (ours)", "NCC (diss.)", "CC (ours)", "CC (diss.)", "SSD (ours)", "SSD (diss.)"};
            for (int row = 0; row < 12; ++row) {
                std::vector<std::string> cells{kRowNames[row]};
                for (int m = 0; m < 3; ++m) {
                    const double v = mean(m, keys[row]);
                    cells.push_back(row < 3 ? fmt(v, 4) : row < 9 ? fmt(v, 1) : percent(v));
                    cells.push_back(kPublished[row][m]);
                }
                t.rows.push_back(cells);
            }
            std::vector<std::string> best{"Best-scoring hypothesis, distance to truth (m)"};
            for (int m = 0; m < 3; ++m) best.push_back(fmt(mean(m, "best_distance_m"), 1)), best.push_back("-");
            t.rows.push_back(best);
            t.write(mc.out, "table_3_4_" + map);
            md += t.markdown() + "\n";
            for (const Json* r : rs)
                if (r->contains("series") && mc.plots) {
                    std::vector<std::vector<double>> cols(4);
                    std::vector<Json> pts(r->at("series").begin(), r->at("series").end());
                    std::sort(pts.begin(), pts.end(), [](const Json& a, const Json& b) { return a[0].get<double>() < b[0].get<double>(); });
                    for (std::size_t i = 0; i < pts.size(); ++i) {
                        cols[0].push_back(static_cast<double>(i));
                        for (int m = 0; m < 3; ++m) cols[m + 1].push_back(pts[i][m + 1].get<double>());
                    }
                    line_plot(mc.out + "/fig_3_4_" + map + ".png", "Fig 3.4 (" + map + "): similarity of 500 hypotheses, sorted by distance to truth",
                              "hypothesis (0 = nearest the truth)", "similarity", cols, {"NCC", "CC", "SSD"},
                              {.x_tic_step = 0, .vertical_lines = {4.5}});
                }
        }
        return md;
    }

private:
    std::string orthophoto_;  // "" when absent
};

}  // namespace

std::unique_ptr<Study> make_metrics_study(std::string orthophoto) { return std::make_unique<MetricsStudy>(std::move(orthophoto)); }

}  // namespace trn::experiments
