#include "trn/energy/plots.hpp"

#include <algorithm>
#include <cmath>
#include <numeric>
#include <sstream>

#include "trn/error.hpp"
#include "trn/io/gnuplot.hpp"

namespace trn::energy {
namespace {

using io::gnuplot_string;

// One number per line, full precision.
std::string column(const std::vector<double>& values) {
    std::ostringstream d;
    d.precision(12);
    for (double x : values) d << x << "\n";
    return d.str();
}

// A job drawing `png`: the script, data and log are named after the image's plain basename.
io::GnuplotJob job_for(const io::PlotTarget& target) {
    io::GnuplotJob job;
    job.folder = target.folder;
    job.script_name = target.name + ".gp";
    job.log_name = target.name + ".log";
    job.images = {target};
    return job;
}

}  // namespace

void plot_power_trace(const PowerTrace& trace, const RunReport& run, const std::string& png) {
    if (trace.size() == 0) throw Error("plot " + png + ": the power trace is empty");
    const io::PlotTarget target = io::plot_target(png);
    io::GnuplotJob job = job_for(target);
    const std::string dat = target.name + ".dat";
    const double t0 = run.frames.empty() ? trace.t.front() : run.frames.front().energy.start;
    std::ostringstream d;
    d.precision(10);
    for (std::size_t i = 0; i < trace.size(); ++i) d << trace.t[i] - t0 << " " << trace.w[i] << "\n";
    job.data.emplace_back(dat, d.str());
    std::ostringstream s;
    s << io::gnuplot_png_terminal(1400, 500) << "set output " << gnuplot_string(target.name) << "\n";
    s << "set title " << gnuplot_string("Power trace with frames shaded: " + run.platform) << "\n";
    s << "set xlabel 'time from first frame start (s)'\nset ylabel 'power (W)'\nset grid\n";
    int n = 1;
    for (const auto& f : run.frames)
        s << "set object " << n++ << " rect from " << f.energy.start - t0 << ", graph 0 to " << f.energy.end - t0
          << ", graph 1 fc rgb '" << (f.energy.flag.empty() ? "#f4a582" : "#bbbbbb") << "' fs solid 0.4 noborder behind\n";
    s << "plot " << gnuplot_string(dat) << " using 1:2 with linespoints pt 7 ps 0.3 lc rgb '#2166ac' title 'power', "
      << run.idle_w << " with lines dt 2 lc rgb 'black' title 'idle baseline'\n";
    job.script = s.str();
    io::run_gnuplot(job);
}

void plot_histograms(const std::vector<PlotSeries>& series, const std::string& png, const std::string& xlabel) {
    if (series.empty()) throw Error("plot " + png + ": no data");
    const io::PlotTarget target = io::plot_target(png);
    io::GnuplotJob job = job_for(target);
    std::ostringstream s;
    const int rows = static_cast<int>(series.size());
    s << io::gnuplot_png_terminal(900, 280 * rows) << "set output " << gnuplot_string(target.name) << "\n";
    s << "set multiplot layout " << rows << ",1\nset style fill solid 0.6 border -1\nset grid\nset ylabel 'frames'\n";
    for (std::size_t k = 0; k < series.size(); ++k) {
        const auto& v = series[k].values;
        const std::string dat = target.name + "." + std::to_string(k) + ".dat";
        job.data.emplace_back(dat, column(v));
        if (v.empty()) continue;
        const auto [lo, hi] = std::minmax_element(v.begin(), v.end());
        const double mean = std::accumulate(v.begin(), v.end(), 0.0) / v.size();
        const int bins = std::clamp(static_cast<int>(std::sqrt(static_cast<double>(v.size()))), 5, 40);
        const double width = *hi > *lo ? (*hi - *lo) / bins : std::max(std::abs(*lo) * 1e-3, 1e-9);
        s << "set title " << gnuplot_string(series[k].name + " (n = " + std::to_string(v.size()) + ")") << "\nset xlabel "
          << gnuplot_string(xlabel) << "\n";
        s << "bw = " << width << "\nlo = " << *lo << "\nbin(x) = lo + bw * floor((x - lo) / bw) + bw / 2\nset boxwidth bw absolute\n";
        s << "set arrow 1 from " << mean << ", graph 0 to " << mean << ", graph 1 nohead lw 2 lc rgb 'red'\n";
        s << "plot " << gnuplot_string(dat) << " using (bin($1)):(1.0) smooth frequency with boxes lc rgb '#4393c3' title 'energy per frame', "
          << "NaN with lines lw 2 lc rgb 'red' title sprintf('mean %.4g', " << mean << ")\nunset arrow 1\n";
    }
    s << "unset multiplot\n";
    job.script = s.str();
    io::run_gnuplot(job);
}

void plot_boxes(const std::vector<PlotSeries>& series, const std::string& png, const std::string& ylabel) {
    if (series.empty()) throw Error("plot " + png + ": no data");
    const io::PlotTarget target = io::plot_target(png);
    io::GnuplotJob job = job_for(target);
    std::ostringstream s;
    s << io::gnuplot_png_terminal(300 + 180 * static_cast<int>(series.size()), 600) << "set output " << gnuplot_string(target.name) << "\n";
    s << "set style data boxplot\nset style boxplot outliers pointtype 7\nset style fill solid 0.4 border -1\nset grid ytics\n";
    s << "set ylabel " << gnuplot_string(ylabel) << "\nset xtics (";
    for (std::size_t k = 0; k < series.size(); ++k) s << (k ? ", " : "") << gnuplot_string(series[k].name) << " " << k + 1;
    s << ") rotate by -20\nunset key\nplot ";
    for (std::size_t k = 0; k < series.size(); ++k) {
        const std::string dat = target.name + "." + std::to_string(k) + ".dat";
        job.data.emplace_back(dat, column(series[k].values));
        s << (k ? ", " : "") << gnuplot_string(dat) << " using (" << k + 1 << "):1";
    }
    s << "\n";
    job.script = s.str();
    io::run_gnuplot(job);
}

}  // namespace trn::energy
