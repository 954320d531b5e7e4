#pragma once
// Figures drawn by gnuplot (run as a subprocess; scripts and data files are kept next to each
// PNG so a figure can be restyled by hand): the power trace with frames shaded, per-platform
// energy histograms with the mean marked (the dissertation's Fig. 3.3), and box plots.
// A missing gnuplot is a trn::Error saying so; nothing else depends on it.
#include <string>
#include <vector>

#include "trn/energy/run_report.hpp"
#include "trn/energy/trace.hpp"

namespace trn::energy {

// Full path of gnuplot on PATH, or "" when there is none.
std::string find_gnuplot();

void plot_power_trace(const PowerTrace& trace, const RunReport& run, const std::string& png);

struct PlotSeries {
    std::string name;
    std::vector<double> values;
};
// One histogram panel per series, mean as a vertical line.
void plot_histograms(const std::vector<PlotSeries>& series, const std::string& png, const std::string& xlabel);
// One box (quartiles, whiskers at 1.5 IQR, outliers) per series.
void plot_boxes(const std::vector<PlotSeries>& series, const std::string& png, const std::string& ylabel);

}  // namespace trn::energy
