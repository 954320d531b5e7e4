#include "trn/energy/plots.hpp"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <numeric>
#include <sstream>

#include "trn/error.hpp"
#include "trn/io/gnuplot.hpp"

namespace trn::energy {
namespace {

using io::gnuplot_string;

// gnuplot reads an explicit tic label as a format string ("100% load" drew "100 1.000000oad", and
// "%s" failed the plot): a literal % is written %%.
std::string tic_label(const std::string& text) {
    std::string out;
    for (const char c : text) out += c == '%' ? std::string("%%") : std::string(1, c);
    return out;
}

// One number per line, full precision.
std::string column(const std::vector<double>& values) {
    std::ostringstream d;
    d.precision(12);
    for (double x : values) d << x << "\n";
    return d.str();
}

// A job drawing `image`: the script, data and log are named after the image's plain basename.
io::GnuplotJob job_for(const io::PlotTarget& target) {
    io::GnuplotJob job;
    job.folder = target.folder;
    job.script_name = target.name + ".gp";
    job.log_name = target.name + ".log";
    job.images = {target};
    return job;
}

bool ends_with(const std::string& s, const char* suffix) {
    const std::string x(suffix);
    if (s.size() < x.size()) return false;
    std::string tail = s.substr(s.size() - x.size());
    std::transform(tail.begin(), tail.end(), tail.begin(), [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
    return tail == x;
}

double mean_of(const std::vector<double>& v) { return std::accumulate(v.begin(), v.end(), 0.0) / static_cast<double>(v.size()); }

}  // namespace

std::string terminal_for(const std::string& image, int w, int h) {
    char buf[160];
    if (ends_with(image, ".pdf")) {
        std::snprintf(buf, sizeof buf, "set terminal pdfcairo size %.2fin,%.2fin noenhanced font 'Sans,9'\n", w / 100.0, h / 100.0);
        return buf;
    }
    if (ends_with(image, ".svg")) {
        std::snprintf(buf, sizeof buf, "set terminal svg size %d,%d noenhanced\n", w, h);
        return buf;
    }
    return io::gnuplot_png_terminal(w, h);
}

HistogramBins shared_bins(const std::vector<PlotSeries>& series) {
    double lo = INFINITY, hi = -INFINITY;
    for (const auto& s : series)
        for (double v : s.values) lo = std::min(lo, v), hi = std::max(hi, v);
    HistogramBins b;
    if (!(hi >= lo)) return b;  // no values at all
    if (!(hi > lo)) {
        b.width = std::max(std::abs(lo) * 1e-3, 1e-9);
        b.lo = lo - b.width / 2, b.bins = 1;
        return b;
    }
    // The narrowest series decides the width (sqrt rule, 5..40 bins over its own range), so a
    // platform with a tight distribution is not a single bar beside a wide one; at most 120 bins
    // across the shared range.
    double width = (hi - lo) / 120;
    double narrowest = INFINITY;
    for (const auto& s : series) {
        if (s.values.size() < 2) continue;
        const auto [a, z] = std::minmax_element(s.values.begin(), s.values.end());
        if (*z > *a) narrowest = std::min(narrowest, (*z - *a) / std::clamp(std::sqrt(static_cast<double>(s.values.size())), 5.0, 40.0));
    }
    if (std::isfinite(narrowest)) width = std::max(width, narrowest);
    else width = (hi - lo) / 10;
    b.width = width;
    b.lo = lo;
    // The maximum lies inside the last bin rather than on its right edge.
    b.bins = static_cast<int>(std::floor((hi - lo) / width)) + 1;
    return b;
}

void plot_power_trace(const PowerTrace& trace, const RunReport& run, const std::string& image, std::size_t zoom_frames) {
    if (trace.size() == 0) throw Error("plot " + image + ": the power trace is empty");
    const io::PlotTarget target = io::plot_target(image);
    io::GnuplotJob job = job_for(target);
    const std::string dat = target.name + ".dat";
    const double t0 = run.frames.empty() ? trace.t.front() : run.frames.front().energy.start;
    std::ostringstream d;
    d.precision(10);
    for (std::size_t i = 0; i < trace.size(); ++i) d << trace.t[i] - t0 << " " << trace.w[i] << "\n";
    job.data.emplace_back(dat, d.str());
    const bool zoom = zoom_frames > 0 && !run.frames.empty();
    std::ostringstream s;
    s << terminal_for(target.path, 1400, zoom ? 900 : 500) << "set output " << gnuplot_string(target.name) << "\n";
    if (zoom) s << "set multiplot layout 2,1\n";
    s << "set title " << gnuplot_string("Power trace with frames shaded: " + run.platform) << "\n";
    s << "set xlabel 'time from first frame start (s)'\nset ylabel 'power (W)'\nset grid\nset key outside right top\n";
    int n = 1;
    for (const auto& f : run.frames)
        s << "set object " << n++ << " rect from " << f.energy.start - t0 << ", graph 0 to " << f.energy.end - t0
          << ", graph 1 fc rgb '" << (f.energy.flag.empty() ? "#f4a582" : "#bbbbbb") << "' fs solid 0.4 noborder behind\n";
    const std::string plot = "plot " + gnuplot_string(dat) + " using 1:2 with linespoints pt 7 ps 0.3 lc rgb '#2166ac' title 'power', " +
                             std::to_string(run.idle_w) + " with lines dt 2 lc rgb 'black' title 'idle baseline'\n";
    s << plot;
    if (zoom) {
        // The first few frames at sample resolution: each frame's start (solid) and end (dashed)
        // marker as a vertical line, labelled with its id, over the shading.
        const std::size_t k = std::min(zoom_frames, run.frames.size());
        const auto& first = run.frames.front().energy;
        const auto& last = run.frames[k - 1].energy;
        const double pad = 0.25 * std::max(last.end - first.start, 1e-6) / static_cast<double>(k);
        s << "set title " << gnuplot_string("Zoom: first " + std::to_string(k) + " frame(s) with their start/end markers") << "\n";
        s << "set xrange [" << first.start - t0 - pad << ":" << last.end - t0 + pad << "]\n";
        for (std::size_t i = 0; i < k; ++i) {
            const auto& f = run.frames[i].energy;
            s << "set arrow " << 2 * i + 1 << " from " << f.start - t0 << ", graph 0 to " << f.start - t0 << ", graph 1 nohead lw 1.5 lc rgb '#b2182b'\n";
            s << "set arrow " << 2 * i + 2 << " from " << f.end - t0 << ", graph 0 to " << f.end - t0 << ", graph 1 nohead lw 1.5 dt 2 lc rgb '#b2182b'\n";
            s << "set label " << i + 1 << " " << gnuplot_string("frame " + std::to_string(f.id)) << " at " << f.start - t0 << ", graph 0.95 offset 0.3,0\n";
        }
        s << "plot " << gnuplot_string(dat) << " using 1:2 with linespoints pt 7 ps 0.6 lc rgb '#2166ac' title 'power', " << run.idle_w
          << " with lines dt 2 lc rgb 'black' title 'idle baseline', NaN with lines lw 1.5 lc rgb '#b2182b' title 'frame start', "
          << "NaN with lines lw 1.5 dt 2 lc rgb '#b2182b' title 'frame end'\n";
        s << "unset multiplot\n";
    }
    job.script = s.str();
    io::run_gnuplot(job);
}

void plot_histograms(const std::vector<PlotSeries>& series, const std::string& image, const std::string& xlabel) {
    if (series.empty()) throw Error("plot " + image + ": no data");
    const io::PlotTarget target = io::plot_target(image);
    io::GnuplotJob job = job_for(target);
    const HistogramBins bins = shared_bins(series);
    const double x_lo = bins.lo - 0.5 * bins.width, x_hi = bins.lo + (bins.bins + 0.5) * bins.width;
    std::ostringstream s;
    const int rows = static_cast<int>(series.size());
    s << terminal_for(target.path, 1000, 280 * rows) << "set output " << gnuplot_string(target.name) << "\n";
    s << "set multiplot layout " << rows << ",1\nset style fill solid 0.6 border -1\nset grid\nset ylabel 'frames'\n";
    // Every panel on the same x range and bins, so platforms compare by eye; y from 0; the key
    // outside the plot area on the right, where it cannot cover a bar.
    s << "set xrange [" << x_lo << ":" << x_hi << "]\nset yrange [0:*]\nset key outside right top\n";
    // Fixed margins: the panels' x axes line up whatever the y labels' and keys' widths.
    s << "set lmargin at screen 0.09\nset rmargin at screen 0.74\n";
    s << "bw = " << bins.width << "\nlo = " << bins.lo << "\nbin(x) = lo + bw * floor((x - lo) / bw) + bw / 2\nset boxwidth bw absolute\n";
    for (std::size_t k = 0; k < series.size(); ++k) {
        const auto& v = series[k].values;
        const std::string dat = target.name + "." + std::to_string(k) + ".dat";
        job.data.emplace_back(dat, column(v));
        s << "set title " << gnuplot_string(series[k].name + " (n = " + std::to_string(v.size()) + ")") << "\nset xlabel " << gnuplot_string(xlabel) << "\n";
        if (v.empty()) {
            s << "plot NaN title 'no usable frames'\n";
            continue;
        }
        const double mean = mean_of(v);
        s << "set arrow 1 from " << mean << ", graph 0 to " << mean << ", graph 1 nohead lw 2 lc rgb 'red' front\n";
        s << "plot " << gnuplot_string(dat) << " using (bin($1)):(1.0) smooth frequency with boxes lc rgb '#4393c3' title 'energy per frame', "
          << "NaN with lines lw 2 lc rgb 'red' title sprintf('mean %.4g', " << mean << ")\nunset arrow 1\n";
    }
    s << "unset multiplot\n";
    job.script = s.str();
    io::run_gnuplot(job);
}

void plot_boxes(const std::vector<PlotSeries>& series, const std::string& image, const std::string& ylabel) {
    if (series.empty()) throw Error("plot " + image + ": no data");
    const io::PlotTarget target = io::plot_target(image);
    io::GnuplotJob job = job_for(target);
    std::ostringstream s;
    s << terminal_for(target.path, 420 + 180 * static_cast<int>(series.size()), 600) << "set output " << gnuplot_string(target.name) << "\n";
    s << "set style boxplot outliers pointtype 7\nset style fill solid 0.4 border -1\nset grid ytics\n";
    s << "set ylabel " << gnuplot_string(ylabel) << "\nset xtics (";
    for (std::size_t k = 0; k < series.size(); ++k) s << (k ? ", " : "") << gnuplot_string(tic_label(series[k].name)) << " " << k + 1;
    s << ") rotate by -20\nset xrange [0.4:" << series.size() + 0.6 << "]\nset key outside right top\nplot ";
    std::ostringstream means;
    means.precision(12);
    for (std::size_t k = 0; k < series.size(); ++k) {
        const std::string dat = target.name + "." + std::to_string(k) + ".dat";
        job.data.emplace_back(dat, column(series[k].values));
        s << (k ? ", " : "") << gnuplot_string(dat) << " using (" << k + 1 << "):1 with boxplot lc rgb '#4393c3' " << (k ? "notitle" : "title 'quartiles, 1.5 IQR'");
        if (!series[k].values.empty()) means << k + 1 << " " << mean_of(series[k].values) << "\n";
    }
    const std::string mean_dat = target.name + ".means.dat";
    job.data.emplace_back(mean_dat, means.str());
    s << ", " << gnuplot_string(mean_dat) << " using 1:2 with points pt 9 ps 2 lc rgb 'red' title 'mean'\n";
    job.script = s.str();
    io::run_gnuplot(job);
}

}  // namespace trn::energy
