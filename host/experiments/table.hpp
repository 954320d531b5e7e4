#pragma once
// A results table written as Markdown (for RESULTS.md) and CSV (for tools); cells are text so the
// dissertation's numbers can sit next to ours exactly as published.
#include <string>
#include <vector>

namespace trn::experiments {

struct Table {
    std::string title;
    std::vector<std::string> header;
    std::vector<std::vector<std::string>> rows;

    std::string markdown() const;
    void write(const std::string& folder, const std::string& stem) const;  // stem.md and stem.csv
};

std::string fmt(double value, int decimals = 2);  // "n/a" for non-finite
std::string percent(double value, int decimals = 2);

// Extra marks on a line plot, as numbers (never script text).
struct LinePlotMarks {
    double x_tic_step = 0;               // > 0: a tic every step on the x axis
    std::vector<double> vertical_lines;  // dashed vertical lines at these x
};

// A line plot with gnuplot: columns of `data` (x first) drawn as lines titled `titles`. The texts go
// through trn::io::gnuplot_string; the script, data and log sit next to the PNG (trn::io::run_gnuplot).
// Skipped with a message on stderr when gnuplot is missing (tables do not depend on it).
void line_plot(const std::string& png, const std::string& title, const std::string& xlabel, const std::string& ylabel,
               const std::vector<std::vector<double>>& data, const std::vector<std::string>& titles, const LinePlotMarks& marks = {});

}  // namespace trn::experiments
