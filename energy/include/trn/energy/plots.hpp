#pragma once
// Figures drawn by gnuplot through trn::io::run_gnuplot (no shell; labels such as platform names
// enter the script only as trn::io::gnuplot_string): the power trace with frames shaded and a
// zoomed panel of a few frames with their start/end markers, per-platform energy histograms on
// one shared x range with the mean marked (the dissertation's Fig. 3.3), and box plots with the
// mean marked. The image format follows the file name: .pdf (pdfcairo), .svg, else PNG. Keys sit
// outside the plot area so they never cover bars. The script, data files and gnuplot's log are
// kept next to each image, named after it (trn::io::plot_target), so a figure can be restyled by
// hand. A missing gnuplot is a trn::Error saying so (trn::io::gnuplot_available() tells
// beforehand); nothing else depends on it.
#include <string>
#include <vector>

#include "trn/energy/run_report.hpp"
#include "trn/energy/trace.hpp"
#include "trn/export.hpp"

TRN_API_BEGIN
namespace trn::energy {

// `zoom_frames`: frames shown in the lower, zoomed panel (0: no zoom panel).
void plot_power_trace(const PowerTrace& trace, const RunReport& run, const std::string& image, std::size_t zoom_frames = 3);

struct PlotSeries {
    std::string name;
    std::vector<double> values;
};
// One histogram panel per series, all on the same x range and bins, mean as a vertical line.
void plot_histograms(const std::vector<PlotSeries>& series, const std::string& image, const std::string& xlabel);
// One box (quartiles, whiskers at 1.5 IQR, outliers) per series, the mean as a marked point.
void plot_boxes(const std::vector<PlotSeries>& series, const std::string& image, const std::string& ylabel);

// Shared bins for histograms of several series: width and first edge such that every value
// falls inside [lo, lo + bins * width) (the largest too, so no bar is cut at either end).
struct HistogramBins {
    double lo = 0, width = 1;
    int bins = 1;
};
HistogramBins shared_bins(const std::vector<PlotSeries>& series);
// "set terminal ..." for the image's extension (.pdf, .svg, else PNG), sized in pixels at 100 dpi.
std::string terminal_for(const std::string& image, int width_px, int height_px);

}  // namespace trn::energy
TRN_API_END
