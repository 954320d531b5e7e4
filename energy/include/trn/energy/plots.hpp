#pragma once
// Figures drawn by gnuplot through trn::io::run_gnuplot (no shell; labels such as platform names
// enter the script only as trn::io::gnuplot_string): the power trace with frames shaded,
// per-platform energy histograms with the mean marked (the dissertation's Fig. 3.3), and box plots.
// The script, data files and gnuplot's log are kept next to each PNG, named after it
// (trn::io::plot_target), so a figure can be restyled by hand. A missing gnuplot is a trn::Error
// saying so (trn::io::gnuplot_available() tells beforehand); nothing else depends on it.
#include <string>
#include <vector>

#include "trn/energy/run_report.hpp"
#include "trn/energy/trace.hpp"
#include "trn/export.hpp"

TRN_API_BEGIN
namespace trn::energy {

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
TRN_API_END
