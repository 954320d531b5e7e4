#include "table.hpp"

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <iostream>
#include <sstream>

#include "trn/error.hpp"
#include "trn/io/atomic_file.hpp"
#include "trn/io/gnuplot.hpp"

namespace trn::experiments {

std::string fmt(double value, int decimals) {
    if (!std::isfinite(value)) return "n/a";
    char buf[64];
    std::snprintf(buf, sizeof buf, "%.*f", decimals, value);
    return buf;
}

std::string percent(double value, int decimals) { return std::isfinite(value) ? fmt(value, decimals) + "%" : "n/a"; }

std::string Table::markdown() const {
    std::string s = "**" + title + "**\n\n|";
    for (const auto& h : header) s += " " + h + " |";
    s += "\n|";
    for (std::size_t i = 0; i < header.size(); ++i) s += i == 0 ? " --- |" : " ---: |";
    s += "\n";
    for (const auto& row : rows) {
        s += "|";
        for (const auto& c : row) s += " " + c + " |";
        s += "\n";
    }
    return s;
}

namespace {
std::string csv_cell(const std::string& c) {
    if (c.find_first_of(",\"\n") == std::string::npos) return c;
    std::string q = "\"";
    for (char ch : c) q += ch == '"' ? std::string("\"\"") : std::string(1, ch);
    return q + "\"";
}
}  // namespace

void Table::write(const std::string& folder, const std::string& stem) const {
    std::string csv;
    auto add_row = [&csv](const std::vector<std::string>& cells) {
        for (std::size_t i = 0; i < cells.size(); ++i) {
            if (i) csv += ',';
            csv += csv_cell(cells[i]);
        }
        csv += '\n';
    };
    add_row(header);
    for (const auto& row : rows) add_row(row);
    io::write_file_atomic(folder + "/" + stem + ".md", markdown());
    io::write_file_atomic(folder + "/" + stem + ".csv", csv);
}

void line_plot(const std::string& png, const std::string& title, const std::string& xlabel, const std::string& ylabel,
               const std::vector<std::vector<double>>& data, const std::vector<std::string>& titles, const LinePlotMarks& marks) {
    if (!io::gnuplot_available()) {
        std::cerr << "experiment: gnuplot not found, skipping " << png << "\n";
        return;
    }
    const io::PlotTarget target = io::plot_target(png);
    const std::string tsv = target.name + ".tsv";
    std::ostringstream table;
    const std::size_t n = data.empty() ? 0 : data[0].size();
    for (std::size_t r = 0; r < n; ++r) {
        for (std::size_t c = 0; c < data.size(); ++c) table << (c ? "\t" : "") << (r < data[c].size() ? data[c][r] : NAN);
        table << "\n";
    }
    // Every text (titles, labels, column titles) enters the script only as a gnuplot_string.
    using io::gnuplot_string;
    std::ostringstream gp;
    gp << io::gnuplot_png_terminal(1000, 600, "sans,11") << "set output " << gnuplot_string(target.name) << "\nset title "
       << gnuplot_string(title) << "\nset xlabel " << gnuplot_string(xlabel) << "\nset ylabel " << gnuplot_string(ylabel)
       << "\nset grid\nset key outside right\n";
    if (marks.x_tic_step > 0) gp << "set xtics " << marks.x_tic_step << "\n";
    for (double x : marks.vertical_lines) gp << "set arrow from " << x << ", graph 0 to " << x << ", graph 1 nohead dt 2\n";
    gp << "plot ";
    for (std::size_t c = 1; c < data.size(); ++c)
        gp << (c > 1 ? ", " : "") << gnuplot_string(tsv) << " using 1:" << c + 1 << " with lines lw 2 title "
           << gnuplot_string(c - 1 < titles.size() ? titles[c - 1] : "");
    gp << "\n";
    io::run_gnuplot({target.folder, target.name + ".gp", gp.str(), {{tsv, table.str()}}, target.name + ".log", {target}});
}

}  // namespace trn::experiments
