// `heading` [dissertation 3.3, Table 3.5, Fig 3.5]: how much NCC drops when the frame's heading is
// wrong by +-2, 5, 10 degrees, averaged over many frames, and the full-circle curve. Each frame is
// scored at the true position with every heading offset in one Backend::score call (a pose with yaw
// + d samples the map exactly as the frame rotated by d about its centre would).
#include <cmath>

#include "study.hpp"
#include "table.hpp"
#include "trn/filter/scorer.hpp"
#include "world.hpp"
#include "trn/detail/angles.hpp"

namespace trn::experiments {
namespace {

const int kTableOffsets[6] = {10, 5, 2, -2, -5, -10};
const char* kPublished[6] = {"67.78", "34.59", "9.38", "10.15", "35.49", "62.08"};

std::vector<int> offsets_deg() {
    std::vector<int> o;
    for (int d = -180; d <= 180; d += 2) o.push_back(d);
    for (int d : {5, -5}) o.push_back(d);
    return o;
}

class HeadingStudy : public Study {
public:
    explicit HeadingStudy(std::string orthophoto) : orthophoto_(std::move(orthophoto)) {}
    std::string name() const override { return "heading"; }
    Json config(bool quick) const override {
        return {{"frames_per_map", quick ? 24 : 500}, {"frames_per_job", quick ? 12 : 50}, {"altitude_m", 200},
                {"camera", "640x480 60deg"},          {"template_width", 160},
                {"procedural_map", "forest 1200 m, 1 m/px, map 2008 / frames 2010"},
                {"orthophoto", orthophoto_.empty() ? "absent" : "present (0.5 m/px, frames from the map aged 2 years)"}};
    }
    std::vector<Json> jobs(const Json& c) const override {
        std::vector<Json> out;
        std::vector<std::string> maps{"procedural"};
        if (c.at("orthophoto") != "absent") maps.push_back("orthophoto");
        const int per = c.at("frames_per_job"), total = c.at("frames_per_map");
        for (const auto& m : maps)
            for (int first = 0; first < total; first += per)
                out.push_back({{"id", m + "-" + std::to_string(first)}, {"map", m}, {"first", first}, {"count", std::min(per, total - first)}});
        return out;
    }

    std::string inputs_key(const Json& p) const override { return p.at("map"); }  // the map pair of study_map_pair
    Json run_job(const Json& c, const Json& p, JobContext& ctx) const override {
        const bool ortho = p.at("map") == "orthophoto";
        const auto [map, world] = study_map_pair(ortho ? orthophoto_ : std::string(), ctx.seed);
        const sim::Camera camera;
        const double altitude = c.at("altitude_m"), scale = sim::template_scale(camera, altitude, map->metres_per_pixel);
        const double margin = 0.5 * std::hypot(camera.width, camera.height) * scale + 2;
        filter::BackendScorerOptions so;
        so.template_width = c.at("template_width");
        filter::BackendScorer scorer(ctx.backend, map->image.view(), so);
        const std::vector<int> offsets = offsets_deg();
        std::vector<double> sum_change(offsets.size(), 0), sum_ncc(offsets.size(), 0);
        int used = 0, skipped = 0;
        std::vector<Pose> poses(offsets.size());
        std::vector<ParticleScore> scores(offsets.size());
        const int first = p.at("first"), count = p.at("count");
        for (int f = first; f < first + count; ++f) {
            Rng rng(mix_seed(ctx.seed, 2000 + f + (ortho ? 700000 : 0)));
            const double x = rng.uniform(margin, map->image.width - margin), y = rng.uniform(margin, map->image.height - margin);
            const double yaw = rng.uniform(-kPi, kPi);
            const GrayImage frame = render_at(*world, camera, x, y, yaw, altitude, mix_seed(ctx.seed, 3000 + f));
            for (std::size_t i = 0; i < offsets.size(); ++i)
                poses[i] = {static_cast<float>(x), static_cast<float>(y), static_cast<float>(yaw + offsets[i] * kPi / 180), 1};
            scorer.score(frame.view(), scale, poses, scores, nullptr);
            const std::size_t zero = 90;  // offsets[90] == 0
            const double base = scores[zero].ncc;
            // A relative change is meaningless when the aligned frame does not correlate at all.
            if (!scores[zero].valid() || base <= 0.05) {
                ++skipped;
                continue;
            }
            ++used;
            for (std::size_t i = 0; i < offsets.size(); ++i) {
                sum_change[i] += 100.0 * (base - scores[i].ncc) / base;
                sum_ncc[i] += scores[i].ncc;
            }
        }
        return {{"offsets_deg", offsets}, {"sum_change_percent", sum_change}, {"sum_ncc", sum_ncc}, {"frames_used", used},
                {"frames_skipped", skipped}};
    }

    std::string merge(const std::vector<Json>& outputs, const MergeContext& mc) const override {
        std::string md;
        const std::vector<int> offsets = offsets_deg();
        for (const std::string map : {"procedural", "orthophoto"}) {
            std::vector<double> change(offsets.size(), 0), ncc(offsets.size(), 0);
            int used = 0, skipped = 0;
            for (const Json& o : outputs) {
                if (o.at("params").at("map") != map) continue;
                const Json& r = o.at("result");
                for (std::size_t i = 0; i < offsets.size(); ++i)
                    change[i] += r.at("sum_change_percent")[i].get<double>(), ncc[i] += r.at("sum_ncc")[i].get<double>();
                used += r.at("frames_used").get<int>();
                skipped += r.at("frames_skipped").get<int>();
            }
            if (used + skipped == 0) continue;
            Table t;
            t.title = "Table 3.5 (" + map + " map): average NCC change vs heading error, " + std::to_string(used) + " frames (" +
                      std::to_string(skipped) + " skipped: aligned NCC <= 0.05)";
            t.header = {"Heading change (deg)", "Average similarity change % (ours)", "(diss.)"};
            for (int k = 0; k < 6; ++k) {
                const auto it = std::find(offsets.begin(), offsets.end(), kTableOffsets[k]);
                const double v = used ? change[it - offsets.begin()] / used : NAN;
                // The sign appended, not `("+" or "") + std::string`: GCC 12's -Wrestrict false positive on aarch64 (GCC PR 105651).
                std::string offset = kTableOffsets[k] > 0 ? "+" : "";
                offset += std::to_string(kTableOffsets[k]);
                t.rows.push_back({offset, fmt(v), kPublished[k]});
            }
            t.write(mc.out, "table_3_5_" + map);
            md += t.markdown() + "\n";
            if (mc.plots && used) {
                std::vector<std::vector<double>> cols(2);
                for (int d = -180; d <= 180; d += 2) {
                    const auto i = std::find(offsets.begin(), offsets.end(), d) - offsets.begin();
                    cols[0].push_back(d);
                    cols[1].push_back(ncc[i] / used);
                }
                line_plot(mc.out + "/fig_3_5_" + map + ".png", "Fig 3.5 (" + map + "): mean NCC vs heading error", "angle from ground truth (deg)",
                          "mean NCC", cols, {"mean NCC over " + std::to_string(used) + " frames"});
            }
        }
        return md;
    }

private:
    std::string orthophoto_;  // "" when absent
};

}  // namespace

std::unique_ptr<Study> make_heading_study(std::string orthophoto) { return std::make_unique<HeadingStudy>(std::move(orthophoto)); }

}  // namespace trn::experiments
