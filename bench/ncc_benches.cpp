// NCC scoring on every backend, and the OpenCV ways a user would score particles instead.
// Names: ncc/<template WxH>/<dense|sparse10|dense-edge|dense-masked:MAP|dense-unmasked:MAP>/N<particles>/<dev:NAME | peer:NAME>
// (dense-edge: the filter's case with every patch over the map's edge; dense-masked:realflight2:
// the filter's case on that flight's real orthomosaic with its no-data, a cloud spread over the
// imagery; dense-unmasked: the same map pixels, poses and frame uploaded without the no-data).
#include <benchmark/benchmark.h>

#include <cmath>
#include <cstdio>
#include <map>

#include <opencv2/core.hpp>
#include <opencv2/imgproc.hpp>

#include "devices.hpp"
#include "inputs.hpp"
#include "old_cpu_ncc.hpp"
#include "register.hpp"
#include "timing.hpp"
#include "trn/scoring_plan.hpp"

namespace trn::bench {
namespace {

// The map goes to each device once, outside every timed loop.
const MapHandle& map_on(const std::string& device) {
    static std::map<std::string, MapHandle> maps;
    MapHandle& h = maps[device];
    if (!h) {
        const cv::Mat& m = bench_map().pixels;
        h = backend_for(device).upload_map({m.ptr<std::uint8_t>(), m.cols, m.rows, static_cast<std::ptrdiff_t>(m.step1())});
    }
    return h;
}

ScoreOptions options_for(bool sparse) {
    ScoreOptions o;
    if (sparse) o.sampling = Sampling::random(0.1, 7);
    return o;
}

// The timed loop of every NCC case: one untimed call first (lazy buffers sized for this batch),
// then each iteration's wall time and the backend's phases. Returns the last scores.
std::vector<ParticleScore> time_scoring(benchmark::State& state, const DeviceEntry& dev, Backend& backend, const MapHandle& map,
                                        const ScoringPlan& plan, const std::vector<Pose>& poses, const std::string& case_name) {
    std::vector<ParticleScore> scores(poses.size());
    PhaseTimes t;
    if (first_time(case_name)) backend.score(map, plan, poses, scores, &t);
    const bool device_clock = has_device_clock(dev.family);
    IterationLog log(state);
    for (auto _ : state) {
        const auto t0 = Clock::now();
        backend.score(map, plan, poses, scores, &t);
        log.add(seconds_since(t0), t, device_clock);
    }
    benchmark::DoNotOptimize(scores.data());
    const auto count = static_cast<std::int64_t>(poses.size());
    log.finish(0, count, "particles/s", 1, double(count) * plan.sample_count());
    return scores;
}

void ncc_on_device(benchmark::State& state, DeviceEntry dev, FrameSize templ_size, bool sparse, int count, bool over_the_edge) {
    Backend& backend = backend_for(dev.name);
    const MapHandle& map = map_on(dev.name);
    const cv::Mat templ = template_from_map(templ_size);
    const ScoringPlan plan =
        make_scoring_plan(GrayView{templ.ptr<std::uint8_t>(), templ.cols, templ.rows, templ.cols}, options_for(sparse));
    const std::vector<Pose> poses = over_the_edge ? poses_over_the_edge(count, templ_size) : poses_around_centre(count);
    const std::vector<ParticleScore> scores = time_scoring(
        state, dev, backend, map, plan, poses,
        "ncc/" + dev.name + "/" + templ_size.text() + (sparse ? "/sparse/" : over_the_edge ? "/dense-edge/" : "/dense/") + std::to_string(count));
    int valid = 0;
    for (const ParticleScore& s : scores) valid += s.valid();
    state.SetLabel(backend.info().device + ", " + std::to_string(plan.sample_count()) + " samples, " + std::to_string(valid) +
                   "/" + std::to_string(count) + " valid, map " + bench_map().source);
}

// A real orthomosaic on each device once, with its no-data or without it.
const MapHandle& masked_map_on(const std::string& device, const MaskedMapInput& in, bool masked) {
    static std::map<std::string, MapHandle> maps;
    MapHandle& h = maps[device + "/" + in.name + (masked ? "/masked" : "/unmasked")];
    if (!h) {
        const GrayView pixels{in.pixels.ptr<std::uint8_t>(), in.pixels.cols, in.pixels.rows, static_cast<std::ptrdiff_t>(in.pixels.step1())};
        const GrayView valid{in.valid.ptr<std::uint8_t>(), in.valid.cols, in.valid.rows, static_cast<std::ptrdiff_t>(in.valid.step1())};
        h = masked ? backend_for(device).upload_map(pixels, valid) : backend_for(device).upload_map(pixels);
    }
    return h;
}

// The filter's case on a real orthomosaic with no-data, masked or not (the same poses and frame):
// the ratio of the two is what the no-data costs a backend.
void ncc_masked_map(benchmark::State& state, DeviceEntry dev, const MaskedMapInput* in, int count, bool masked) {
    Backend& backend = backend_for(dev.name);
    const MapHandle& map = masked_map_on(dev.name, *in, masked);
    const ScoringPlan plan = make_scoring_plan(GrayView{in->templ.ptr<std::uint8_t>(), in->templ.cols, in->templ.rows, in->templ.cols}, {});
    const std::vector<Pose> poses = poses_on_valid(*in, count);
    const std::vector<ParticleScore> scores =
        time_scoring(state, dev, backend, map, plan, poses, "ncc/" + dev.name + "/" + in->name + (masked ? "/masked/" : "/unmasked/") + std::to_string(count));
    int valid = 0;
    double samples = 0;
    for (const ParticleScore& s : scores) valid += s.valid(), samples += s.valid_samples;
    char share[32];
    std::snprintf(share, sizeof share, "%.2f", 100.0 * samples / (double(count) * plan.sample_count()));
    state.SetLabel(backend.info().device + ", " + std::to_string(plan.sample_count()) + " samples, " + std::to_string(valid) + "/" +
                   std::to_string(count) + " valid, " + share + " % of samples used, map " + in->source + (masked ? ", no-data masked" : ", no-data not masked") +
                   ", scale " + std::to_string(in->scale));
}

// Inverse affine (template pixel -> source pixel) of a pose, for cv::warpAffine(WARP_INVERSE_MAP),
// relative to a source whose top-left is at (ox, oy) in the map.
cv::Matx23d pose_matrix(const Pose& p, const cv::Mat& templ, double ox, double oy) {
    const double c = std::cos(p.yaw) * p.scale, s = std::sin(p.yaw) * p.scale;
    const double cx = (templ.cols - 1) / 2.0, cy = (templ.rows - 1) / 2.0;
    return {c, -s, p.x - ox - c * cx + s * cy, s, c, p.y - oy - s * cx - c * cy};
}

enum class Peer { ParticleMatch, WarpStats, WarpOnly };

const char* peer_name(Peer p) {
    return p == Peer::ParticleMatch ? "peer:particle_match" : p == Peer::WarpStats ? "peer:cv_warpAffine_meanstd_dot" : "peer:cv_warpAffine_only";
}

// particle_match: per particle, crop the map around the pose (an ROI, no copy: the cheapest
// reading of "crop"), warp the crop to the template, matchTemplate(TM_CCOEFF_NORMED) -> 1x1.
float particle_match_score(const cv::Mat& map, const cv::Mat& templ, const Pose& p, cv::Mat& patch, cv::Mat& result) {
    const double r = 0.5 * p.scale * std::hypot(templ.cols, templ.rows) + 2;
    const cv::Rect want(int(std::floor(p.x - r)), int(std::floor(p.y - r)), int(std::ceil(2 * r)) + 1, int(std::ceil(2 * r)) + 1);
    const cv::Rect roi = want & cv::Rect(0, 0, map.cols, map.rows);
    const cv::Mat crop = map(roi);
    cv::warpAffine(crop, patch, pose_matrix(p, templ, roi.x, roi.y), templ.size(), cv::INTER_LINEAR | cv::WARP_INVERSE_MAP);
    cv::matchTemplate(patch, templ, result, cv::TM_CCOEFF_NORMED);
    return result.at<float>(0, 0);
}

// warpAffine straight to the patch, then NCC from mean/std and one dot product.
float warp_stats_score(const cv::Mat& map, const cv::Mat& templ, double t_mean, double t_std, const Pose& p, cv::Mat& patch) {
    cv::warpAffine(map, patch, pose_matrix(p, templ, 0, 0), templ.size(), cv::INTER_LINEAR | cv::WARP_INVERSE_MAP);
    cv::Scalar mean, stddev;
    cv::meanStdDev(patch, mean, stddev);
    const double n = double(templ.total());
    const double cov = patch.dot(templ) / n - mean[0] * t_mean;
    return float(cov / (stddev[0] * t_std + 1e-12));
}

void ncc_peer(benchmark::State& state, Peer peer, FrameSize templ_size, int count) {
    const cv::Mat& map = bench_map().pixels;
    const cv::Mat templ = template_from_map(templ_size);
    cv::Scalar t_mean, t_std;
    cv::meanStdDev(templ, t_mean, t_std);
    const std::vector<Pose> poses = poses_around_centre(count);
    std::vector<float> scores(poses.size());
    cv::Mat patch(templ.size(), CV_8UC1), result(1, 1, CV_32FC1);
    auto run_all = [&] {
        for (std::size_t i = 0; i < poses.size(); ++i) {
            switch (peer) {
                case Peer::ParticleMatch: scores[i] = particle_match_score(map, templ, poses[i], patch, result); break;
                case Peer::WarpStats: scores[i] = warp_stats_score(map, templ, t_mean[0], t_std[0], poses[i], patch); break;
                case Peer::WarpOnly:
                    cv::warpAffine(map, patch, pose_matrix(poses[i], templ, 0, 0), templ.size(), cv::INTER_LINEAR | cv::WARP_INVERSE_MAP);
                    scores[i] = patch.at<std::uint8_t>(0, 0);
                    break;
            }
        }
    };
    if (first_time(std::string(peer_name(peer)) + "/" + templ_size.text())) run_all();
    IterationLog log(state);
    for (auto _ : state) {
        const auto t0 = Clock::now();
        run_all();
        log.add(seconds_since(t0));
    }
    benchmark::DoNotOptimize(scores.data());
    log.finish(0, count, "particles/s", 1, double(count) * templ.total());
    state.SetLabel("OpenCV " CV_VERSION ", " + std::to_string(cv::getNumThreads()) + " threads, one call per particle, score[0]=" +
                   std::to_string(scores[0]));
}

// The cpu backend before exact integer scoring (old_cpu_ncc.hpp), dense only: the "before" of
// issue 14's cpu speed targets, measured in the same run as the backend.
void ncc_old_cpu(benchmark::State& state, FrameSize templ_size, int count) {
    static const old_cpu::PackedMap map = old_cpu::pack_map(bench_map().pixels);
    const old_cpu::FloatPlan plan = old_cpu::make_float_plan(template_from_map(templ_size));
    const std::vector<Pose> poses = poses_around_centre(count);
    std::vector<float> scores(poses.size());
    if (first_time("old:cpu_float/" + templ_size.text() + "/" + std::to_string(count))) old_cpu::score(map, plan, poses, scores);
    IterationLog log(state);
    for (auto _ : state) {
        const auto t0 = Clock::now();
        old_cpu::score(map, plan, poses, scores);
        log.add(seconds_since(t0));
    }
    benchmark::DoNotOptimize(scores.data());
    log.finish(0, count, "particles/s", 1, double(count) * double(templ_size.width) * templ_size.height);
    state.SetLabel(std::string("float sums, inner loop ") + (old_cpu::avx2_available() ? "AVX2" : "portable") +
                   ", the cpu backend before exact scoring, score[0]=" + std::to_string(scores[0]));
}

}  // namespace

void register_ncc_benchmarks(const Sweep& sweep) {
    for (const FrameSize& ts : sweep.ncc_templates) {
        for (bool sparse : {false, true}) {
            const std::string prefix = "ncc/" + ts.text() + "/" + (sparse ? "sparse10" : "dense") + "/N";
            for (const DeviceEntry& dev : bench_devices()) {
                for (int n : sweep.ncc_counts) {
                    if (dev.family == "cpu-ref") continue;  // its own, smaller case below
                    benchmark::RegisterBenchmark((prefix + std::to_string(n) + "/dev:" + dev.name).c_str(), ncc_on_device, dev, ts,
                                                 sparse, n, false)
                        ->UseManualTime()->Unit(benchmark::kMillisecond);
                }
                if (dev.family == "cpu-ref")
                    benchmark::RegisterBenchmark((prefix + std::to_string(sweep.ncc_reference_count) + "/dev:" + dev.name).c_str(),
                                                 ncc_on_device, dev, ts, sparse, sweep.ncc_reference_count, false)
                        ->UseManualTime()->Unit(benchmark::kMillisecond);
            }
            if (sparse) continue;  // the peers and the old cpu path have no sparse mode
            for (int n : sweep.ncc_counts)
                benchmark::RegisterBenchmark((prefix + std::to_string(n) + "/old:cpu_float").c_str(), ncc_old_cpu, ts, n)
                    ->UseManualTime()->Unit(benchmark::kMillisecond);
            for (Peer peer : {Peer::ParticleMatch, Peer::WarpStats, Peer::WarpOnly})
                benchmark::RegisterBenchmark((prefix + std::to_string(sweep.ncc_reference_count) + "/" + peer_name(peer)).c_str(), ncc_peer,
                                             peer, ts, sweep.ncc_reference_count)
                    ->UseManualTime()->Unit(benchmark::kMillisecond);
        }
    }
    // The particle filter's case: many particles, a small template; every backend but cpu-ref,
    // and the old cpu path beside them.
    const FrameSize fs = sweep.ncc_filter_template;
    const std::string prefix = "ncc/" + fs.text() + "/dense/N" + std::to_string(sweep.ncc_filter_count);
    for (const DeviceEntry& dev : bench_devices())
        if (dev.family != "cpu-ref")
            benchmark::RegisterBenchmark((prefix + "/dev:" + dev.name).c_str(), ncc_on_device, dev, fs, false, sweep.ncc_filter_count, false)
                ->UseManualTime()->Unit(benchmark::kMillisecond);
    benchmark::RegisterBenchmark((prefix + "/old:cpu_float").c_str(), ncc_old_cpu, fs, sweep.ncc_filter_count)
        ->UseManualTime()->Unit(benchmark::kMillisecond);
    // The same particles' count with every patch over the map's edge: beside the case above, how
    // much a cloud at the border costs each backend.
    const std::string edge = "ncc/" + fs.text() + "/dense-edge/N" + std::to_string(sweep.ncc_filter_count);
    for (const DeviceEntry& dev : bench_devices())
        if (dev.family != "cpu-ref")
            benchmark::RegisterBenchmark((edge + "/dev:" + dev.name).c_str(), ncc_on_device, dev, fs, false, sweep.ncc_filter_count, true)
                ->UseManualTime()->Unit(benchmark::kMillisecond);
    // The same case on the real orthomosaics with no-data (when $TRN_SHARED_DATA has them), each
    // with its no-data masked and, beside it, without: how much the mask costs each backend.
    for (const char* name : {"realflight2", "realflight3"}) {
        const MaskedMapInput* in = masked_map(name, fs);
        if (!in) continue;
        for (bool masked : {true, false}) {
            const std::string case_prefix = "ncc/" + fs.text() + (masked ? "/dense-masked:" : "/dense-unmasked:") + name + "/N" +
                                            std::to_string(sweep.ncc_filter_count);
            for (const DeviceEntry& dev : bench_devices())
                if (dev.family != "cpu-ref")
                    benchmark::RegisterBenchmark((case_prefix + "/dev:" + dev.name).c_str(), ncc_masked_map, dev, in, sweep.ncc_filter_count, masked)
                        ->UseManualTime()->Unit(benchmark::kMillisecond);
        }
    }
}

}  // namespace trn::bench
