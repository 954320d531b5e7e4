#include "trn/energy/plots.hpp"

#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <numeric>
#include <sstream>

#include "trn/energy/stats.hpp"
#include "trn/error.hpp"
#include "trn/io/atomic_file.hpp"

extern char** environ;

namespace trn::energy {
namespace {

void write(const std::string& path, const std::string& text) { io::write_file_atomic(path, text); }

// gnuplot strings are single-quoted; a quote inside is doubled.
std::string quoted_path(const std::string& s) {
    std::string out = "'";
    for (char c : s) out += c == '\'' ? std::string("''") : std::string(1, c);
    return out + "'";
}

// gnuplot draws into `drawn` (a temporary beside `png`); only a finished image is renamed to `png`,
// so a failed or killed gnuplot never leaves a cut image under the final name.
void run_gnuplot(const std::string& script_path, const std::string& png, const std::string& drawn) {
    struct Cleanup {
        const std::string& path;
        ~Cleanup() { std::remove(path.c_str()); }
    } cleanup{drawn};
    const std::string exe = find_gnuplot();
    if (exe.empty()) throw Error("plot " + png + ": gnuplot not found on PATH (install gnuplot-nox, see scripts/install-deps.sh)");
    pid_t pid = 0;
    std::string a0 = exe, a1 = script_path;
    char* argv[] = {a0.data(), a1.data(), nullptr};
    if (posix_spawn(&pid, exe.c_str(), nullptr, nullptr, argv, environ) != 0) throw Error("plot " + png + ": cannot start " + exe);
    int status = 0;
    waitpid(pid, &status, 0);
    if (!WIFEXITED(status) || WEXITSTATUS(status) != 0) throw Error("plot " + png + ": gnuplot failed on " + script_path);
    std::error_code ec;
    if (!std::filesystem::exists(drawn, ec) || std::filesystem::file_size(drawn, ec) == 0) throw Error("plot " + png + ": gnuplot wrote no image");
    std::filesystem::rename(drawn, png, ec);
    if (ec) throw Error("plot " + png + ": cannot replace (" + ec.message() + ")");
}

}  // namespace

std::string find_gnuplot() {
    const char* path = std::getenv("PATH");
    if (!path) return "";
    std::stringstream ss(path);
    std::string dir;
    while (std::getline(ss, dir, ':')) {
        const std::string p = (dir.empty() ? "." : dir) + "/gnuplot";
        if (::access(p.c_str(), X_OK) == 0) return p;
    }
    return "";
}

void plot_power_trace(const PowerTrace& trace, const RunReport& run, const std::string& png) {
    const std::string dat = png + ".dat", gp = png + ".gp", drawn = io::temporary_sibling(png);
    const double t0 = run.frames.empty() ? trace.t.front() : run.frames.front().energy.start;
    std::ostringstream d;
    d.precision(10);
    for (std::size_t i = 0; i < trace.size(); ++i) d << trace.t[i] - t0 << " " << trace.w[i] << "\n";
    write(dat, d.str());
    std::ostringstream s;
    s << "set terminal pngcairo size 1400,500 noenhanced\nset output " << quoted_path(drawn) << "\n";
    s << "set title " << quoted_path("Power trace with frames shaded: " + run.platform) << "\n";
    s << "set xlabel 'time from first frame start (s)'\nset ylabel 'power (W)'\nset grid\n";
    int n = 1;
    for (const auto& f : run.frames)
        s << "set object " << n++ << " rect from " << f.energy.start - t0 << ", graph 0 to " << f.energy.end - t0
          << ", graph 1 fc rgb '" << (f.energy.flag.empty() ? "#f4a582" : "#bbbbbb") << "' fs solid 0.4 noborder behind\n";
    s << "plot " << quoted_path(dat) << " using 1:2 with linespoints pt 7 ps 0.3 lc rgb '#2166ac' title 'power', "
      << run.idle_w << " with lines dt 2 lc rgb 'black' title 'idle baseline'\n";
    write(gp, s.str());
    run_gnuplot(gp, png, drawn);
}

void plot_histograms(const std::vector<PlotSeries>& series, const std::string& png, const std::string& xlabel) {
    if (series.empty()) throw Error("plot " + png + ": no data");
    const std::string gp = png + ".gp", drawn = io::temporary_sibling(png);
    std::ostringstream s;
    const int rows = static_cast<int>(series.size());
    s << "set terminal pngcairo size 900," << 280 * rows << " noenhanced\nset output " << quoted_path(drawn) << "\n";
    s << "set multiplot layout " << rows << ",1\nset style fill solid 0.6 border -1\nset grid\nset ylabel 'frames'\n";
    for (std::size_t k = 0; k < series.size(); ++k) {
        const auto& v = series[k].values;
        const std::string dat = png + "." + std::to_string(k) + ".dat";
        std::ostringstream d;
        d.precision(12);
        for (double x : v) d << x << "\n";
        write(dat, d.str());
        if (v.empty()) continue;
        const auto [lo, hi] = std::minmax_element(v.begin(), v.end());
        const double mean = std::accumulate(v.begin(), v.end(), 0.0) / v.size();
        const int bins = std::clamp(static_cast<int>(std::sqrt(static_cast<double>(v.size()))), 5, 40);
        const double width = *hi > *lo ? (*hi - *lo) / bins : std::max(std::abs(*lo) * 1e-3, 1e-9);
        s << "set title " << quoted_path(series[k].name + " (n = " + std::to_string(v.size()) + ")") << "\nset xlabel " << quoted_path(xlabel) << "\n";
        s << "bw = " << width << "\nlo = " << *lo << "\nbin(x) = lo + bw * floor((x - lo) / bw) + bw / 2\nset boxwidth bw absolute\n";
        s << "set arrow 1 from " << mean << ", graph 0 to " << mean << ", graph 1 nohead lw 2 lc rgb 'red'\n";
        s << "plot " << quoted_path(dat) << " using (bin($1)):(1.0) smooth frequency with boxes lc rgb '#4393c3' title 'energy per frame', "
          << "NaN with lines lw 2 lc rgb 'red' title sprintf('mean %.4g', " << mean << ")\nunset arrow 1\n";
    }
    s << "unset multiplot\n";
    write(gp, s.str());
    run_gnuplot(gp, png, drawn);
}

void plot_boxes(const std::vector<PlotSeries>& series, const std::string& png, const std::string& ylabel) {
    if (series.empty()) throw Error("plot " + png + ": no data");
    const std::string gp = png + ".gp", drawn = io::temporary_sibling(png);
    std::ostringstream s;
    s << "set terminal pngcairo size " << 300 + 180 * series.size() << ",600 noenhanced\nset output " << quoted_path(drawn) << "\n";
    s << "set style data boxplot\nset style boxplot outliers pointtype 7\nset style fill solid 0.4 border -1\nset grid ytics\n";
    s << "set ylabel " << quoted_path(ylabel) << "\nset xtics (";
    for (std::size_t k = 0; k < series.size(); ++k) s << (k ? ", " : "") << quoted_path(series[k].name) << " " << k + 1;
    s << ") rotate by -20\nunset key\nplot ";
    for (std::size_t k = 0; k < series.size(); ++k) {
        const std::string dat = png + "." + std::to_string(k) + ".dat";
        std::ostringstream d;
        d.precision(12);
        for (double x : series[k].values) d << x << "\n";
        write(dat, d.str());
        s << (k ? ", " : "") << quoted_path(dat) << " using (" << k + 1 << "):1";
    }
    s << "\n";
    write(gp, s.str());
    run_gnuplot(gp, png, drawn);
}

}  // namespace trn::energy
