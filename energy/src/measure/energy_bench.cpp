#include "trn/energy/energy_bench.hpp"

#include <algorithm>
#include <cstdio>
#include <nlohmann/json.hpp>
#include <sstream>

#include "sha256.hpp"
#include "trn/energy/background_sampler.hpp"
#include "trn/energy/label_check.hpp"
#include "trn/energy/parsers.hpp"
#include "trn/energy/stats.hpp"
#include "trn/error.hpp"
#include "trn/io/gnuplot.hpp"
#include "trn/io/outside_text.hpp"
#include "trn/io/provenance.hpp"

namespace trn::energy {

BenchResult run_energy_bench(PowerSampler& sampler, const std::vector<BenchTarget>& targets, const BenchConfig& c) {
    if (targets.empty()) throw Error("energy bench: no backend to run");
    if (c.calls_per_frame < 1) throw Error("energy bench: calls per frame must be at least 1");
    check_label(c.platform, "energy bench: platform");  // before the run: it is written into every report after it
    BenchResult res;
    res.sampler = sampler.describe();
    res.period_s = c.period_s;
    std::vector<MarkerFile> runs;
    {
        BackgroundSampler live(sampler, c.period_s, SampleClock::Monotonic);
        for (const auto& t : targets) {
            FrameRunConfig rc = c.run;
            for (const auto& [k, v] : t.meta) rc.meta[k] = v;
            rc.meta["sampler"] = "bench";
            try {
                runs.push_back(run_frames(t.kernel, rc));
            } catch (const std::exception& e) {
                throw Error("energy bench: backend " + t.name + ": " + e.what());
            }
        }
        res.trace = live.stop();
    }
    // The rows come from the trace as written to power.log and read back, so `energy integrate
    // power.log --markers markers-<backend>.csv --clock mono` reproduces them exactly.
    // Read back twice: the first read adds the parser's notes (the plausibility cap), after which
    // writing and reading are a fixpoint, so the hash is that of the power.log the CLI writes.
    res.trace = parse_power_log(format_trnkit_power(res.trace), "power.log", "trnkit");
    const std::string log_text = format_trnkit_power(res.trace);
    res.trace = parse_power_log(log_text, "power.log", "trnkit");
    const std::string log_hash = sha256_hex(log_text);
    for (std::size_t i = 0; i < targets.size(); ++i) {
        IntegrateRequest q;
        q.realtime = false;  // both on CLOCK_MONOTONIC
        q.align = AlignMode::SameClock;
        q.integration = c.integration;
        RunReport r = integrate_run(res.trace, runs[i], q);
        if (!c.platform.empty()) r.platform = c.platform + ":" + r.platform;
        r.log_path = "power.log", r.log_sha256 = log_hash;
        r.markers_path = "markers-" + io::plain_basename(targets[i].name) + ".csv", r.markers_sha256 = sha256_hex(format_markers(runs[i]));
        BenchRow row = bench_row(r, c.platform, targets[i].name, c.calls_per_frame);
        row.markers = runs[i];
        if (row.usable == 0)
            res.warnings.push_back(targets[i].name + ": none of " + std::to_string(row.frames) + " frames is usable (" +
                                   (r.frames.empty() ? std::string("no frames") : r.frames.front().energy.flag) +
                                   "): sample faster (a shorter sampling period) or make frames longer (a larger frame or more particles)");
        for (const auto& w : r.warnings) res.warnings.push_back(targets[i].name + ": " + w);
        res.rows.push_back(std::move(row));
    }
    return res;
}

BenchRow bench_row(const RunReport& r, const std::string& platform, const std::string& target, int calls_per_frame) {
    if (calls_per_frame < 1) throw Error("energy bench: calls per frame must be at least 1");
    BenchRow row;
    row.platform = platform, row.target = target, row.run = r, row.calls_per_frame = calls_per_frame;
    row.frames = r.frames.size();
    row.idle_w = r.idle_w;
    std::vector<double> gross, net;
    double ms = 0, exec = 0, bound = 0, samples = 0, busy_s = 0;
    for (const auto& f : r.frames) {
        if (!f.energy.flag.empty()) continue;
        gross.push_back(f.energy.gross_j), net.push_back(f.energy.net_j);
        ms += f.marker_ms, exec += f.exec_ms, bound += f.energy.error_j, samples += static_cast<double>(f.energy.samples);
        busy_s += f.energy.duration();
    }
    row.usable = gross.size();
    if (row.usable == 0) return row;
    const double n = static_cast<double>(row.usable), k = calls_per_frame;
    row.frame_ms = ms / n / k, row.exec_ms = exec / n / k, row.bound_j = bound / n / k, row.samples_per_frame = samples / n;
    row.frames_per_s = row.frame_ms > 0 ? 1000 / row.frame_ms : 0;
    const Summary g = summarize(gross), e = summarize(net);
    row.gross_j = g.mean / k, row.gross_ci_low = g.ci_low / k, row.gross_ci_high = g.ci_high / k;
    row.net_j = e.mean / k, row.net_ci_low = e.ci_low / k, row.net_ci_high = e.ci_high / k;
    row.busy_w = busy_s > 0 ? g.mean * n / busy_s : 0;
    return row;
}

std::string bench_json(const BenchResult& res) {
    using nlohmann::json;
    json j;
    j["trnkit_energy_bench"] = 1;
    io::add_provenance(j);
    j["sampler"] = res.sampler;
    j["period_s"] = res.period_s;
    j["clock"] = "monotonic";
    j["trace"] = {{"samples", res.trace.size()}, {"quantity", res.trace.quantity}, {"notes", res.trace.notes}};
    j["warnings"] = res.warnings;
    json rows = json::array();
    for (const auto& r : res.rows)
        rows.push_back({{"platform", r.platform}, {"backend", r.target}, {"label", r.run.platform}, {"frames", r.frames}, {"usable", r.usable}, {"calls_per_frame", r.calls_per_frame},
                        {"frame_ms", r.frame_ms}, {"exec_ms", r.exec_ms}, {"frames_per_s", r.frames_per_s}, {"gross_j", r.gross_j},
                        {"gross_ci_j", {r.gross_ci_low, r.gross_ci_high}}, {"net_j", r.net_j}, {"net_ci_j", {r.net_ci_low, r.net_ci_high}},
                        {"bound_j", r.bound_j}, {"idle_w", r.idle_w}, {"busy_w", r.busy_w}, {"samples_per_frame", r.samples_per_frame},
                        {"markers", r.run.markers_path}, {"marker_meta", r.run.marker_meta}});
    j["rows"] = rows;
    return io::json_text(j, 1);  // outside text (paths, labels, notes) made valid UTF-8 first
}

std::string bench_csv(const BenchResult& res) {
    std::ostringstream os;
    os << "platform,backend,frames,usable,calls_per_frame,frame_ms,exec_ms,frames_per_s,gross_j,gross_ci_low_j,gross_ci_high_j,net_j,net_ci_low_j,net_ci_high_j,"
          "bound_j,idle_w,busy_w,samples_per_frame\n";
    char buf[512];
    for (const auto& r : res.rows) {
        std::snprintf(buf, sizeof buf, ",%zu,%zu,%d,%.6f,%.6f,%.6g,%.9g,%.9g,%.9g,%.9g,%.9g,%.9g,%.6g,%.6g,%.6g,%.4g\n", r.frames, r.usable, r.calls_per_frame, r.frame_ms,
                      r.exec_ms, r.frames_per_s, r.gross_j, r.gross_ci_low, r.gross_ci_high, r.net_j, r.net_ci_low, r.net_ci_high, r.bound_j, r.idle_w,
                      r.busy_w, r.samples_per_frame);
        // Labels are quoted (a platform may contain a comma).
        auto quoted = [](std::string s) {
            std::string q = "\"";
            for (char ch : s) q += ch == '"' ? std::string("\"\"") : std::string(1, ch);
            return q + "\"";
        };
        os << quoted(r.platform) << "," << quoted(r.target) << buf;
    }
    return os.str();
}

std::string bench_markdown(const BenchResult& res) {
    std::ostringstream os;
    os << "Energy bench: sampler " << res.sampler << ", period " << res.period_s * 1e3 << " ms, one process clock (CLOCK_MONOTONIC)\n";
    if (!res.rows.empty() && res.rows.front().calls_per_frame > 1)
        os << "A frame is " << res.rows.front().calls_per_frame << " kernel calls; times, rates and joules are per call.\n";
    os << "\n";
    os << "| platform | backend | frames (usable) | frame ms | frames/s | gross mJ/frame [95 % CI] | net mJ/frame [95 % CI] | bound mJ/frame | idle W | busy W |\n";
    os << "|---|---|---|---|---|---|---|---|---|---|\n";
    char buf[512];
    for (const auto& r : res.rows) {
        std::snprintf(buf, sizeof buf, " | %zu (%zu) | %.3f | %.1f | %.4g [%.4g, %.4g] | %.4g [%.4g, %.4g] | %.3g | %.4g | %.4g |\n", r.frames, r.usable,
                      r.frame_ms, r.frames_per_s, 1e3 * r.gross_j, 1e3 * r.gross_ci_low, 1e3 * r.gross_ci_high, 1e3 * r.net_j, 1e3 * r.net_ci_low,
                      1e3 * r.net_ci_high, 1e3 * r.bound_j, r.idle_w, r.busy_w);
        os << "| " << (r.platform.empty() ? "-" : r.platform) << " | " << r.target << buf;
    }
    for (const auto& w : res.warnings) os << "\nwarning: " << w;
    if (!res.warnings.empty()) os << "\n";
    return os.str();
}

namespace {

// gnuplot reads an explicit tic label as a format string: a literal % is written %%.
std::string tic_label(const std::string& text) {
    std::string out;
    for (const char c : text) out += c == '%' ? std::string("%%") : std::string(1, c);
    return out;
}

std::string xtics(const BenchResult& res) {
    std::string s = "set xtics (";
    for (std::size_t k = 0; k < res.rows.size(); ++k) s += (k ? ", " : "") + io::gnuplot_string(tic_label(res.rows[k].target)) + " " + std::to_string(k);
    return s + ")\n";
}

void draw(const std::string& folder, const std::string& name, const std::string& data, const std::string& script, std::size_t bars) {
    io::GnuplotJob job;
    job.folder = folder;
    job.script_name = name + ".gp", job.log_name = name + ".log";
    job.data = {{name + ".dat", data}};
    job.images = {io::PlotTarget{folder, name + ".png", folder + "/" + name + ".png"}};
    job.script = io::gnuplot_png_terminal(300 + 160 * static_cast<int>(std::min<std::size_t>(bars, 20)), 500) + "set output '" + name + ".png'\n" + script;
    io::run_gnuplot(job);
}

}  // namespace

void plot_bench(const BenchResult& res, const std::string& folder) {
    if (res.rows.empty()) throw Error("energy bench: nothing to plot");
    const std::string platform = res.rows.front().platform.empty() ? std::string() : " on " + res.rows.front().platform;
    std::ostringstream d, s;
    d.precision(10);
    // x, gross, gross error, net, net error (mJ): error = integration bound + 95 % CI half-width.
    for (std::size_t k = 0; k < res.rows.size(); ++k) {
        const auto& r = res.rows[k];
        d << k << " " << 1e3 * r.gross_j << " " << 1e3 * (r.bound_j + r.gross_ci_high - r.gross_j) << " " << 1e3 * r.net_j << " "
          << 1e3 * (r.bound_j + r.net_ci_high - r.net_j) << " " << r.frames_per_s << "\n";
    }
    s << "set title " << io::gnuplot_string("Energy per frame" + platform + " (bars: bound + 95 % CI)") << "\n";
    s << "set ylabel 'mJ per frame'\nset grid ytics\nset style fill solid 0.6 border -1\nset boxwidth 0.35\nset xrange [-0.6:" << res.rows.size() - 0.4
      << "]\nset yrange [0:*]\nset key outside top center horizontal\n" << xtics(res);
    s << "plot 'bench_energy.dat' using ($1-0.19):2:3 with boxerrorbars lc rgb '#4393c3' title 'gross', "
         "'' using ($1+0.19):($4 > 0 ? $4 : 0):5 with boxerrorbars lc rgb '#d6604d' title 'net of idle'\n";
    draw(folder, "bench_energy", d.str(), s.str(), res.rows.size());
    std::ostringstream t;
    t << "set title " << io::gnuplot_string("Throughput" + platform) << "\n";
    t << "set ylabel 'frames per second'\nset grid ytics\nset style fill solid 0.6 border -1\nset boxwidth 0.5\nset xrange [-0.6:" << res.rows.size() - 0.4
      << "]\nset yrange [0:*]\nunset key\n" << xtics(res);
    t << "plot 'bench_speed.dat' using 1:6 with boxes lc rgb '#4393c3'\n";
    draw(folder, "bench_speed", d.str(), t.str(), res.rows.size());
}

}  // namespace trn::energy
