#include "table.hpp"

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <iostream>

#include "trn/error.hpp"
#include "trn/io/atomic_file.hpp"

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
    for (std::size_t i = 0; i < header.size(); ++i) csv += (i ? "," : "") + csv_cell(header[i]);
    csv += "\n";
    for (const auto& row : rows) {
        for (std::size_t i = 0; i < row.size(); ++i) csv += (i ? "," : "") + csv_cell(row[i]);
        csv += "\n";
    }
    io::write_file_atomic(folder + "/" + stem + ".md", markdown());
    io::write_file_atomic(folder + "/" + stem + ".csv", csv);
}

void line_plot(const std::string& png, const std::string& title, const std::string& xlabel, const std::string& ylabel,
               const std::vector<std::vector<double>>& data, const std::vector<std::string>& titles, const std::string& extra) {
    if (std::system("command -v gnuplot >/dev/null 2>&1") != 0) {
        std::cerr << "experiment: gnuplot not found, skipping " << png << "\n";
        return;
    }
    const std::string tsv = png + ".tsv", gp = png + ".gp";
    {
        std::ofstream out(tsv);
        const std::size_t n = data.empty() ? 0 : data[0].size();
        for (std::size_t r = 0; r < n; ++r) {
            for (std::size_t c = 0; c < data.size(); ++c) out << (c ? "\t" : "") << (r < data[c].size() ? data[c][r] : NAN);
            out << "\n";
        }
        if (!out) throw Error(tsv + ": write failed");
    }
    {
        std::ofstream out(gp);
        out << "set terminal pngcairo size 1000,600 font 'sans,11'\nset output '" << png << "'\nset title '" << title
            << "'\nset xlabel '" << xlabel << "'\nset ylabel '" << ylabel << "'\nset grid\nset key outside right\n" << extra << "plot ";
        for (std::size_t c = 1; c < data.size(); ++c)
            out << (c > 1 ? ", " : "") << "'" << tsv << "' using 1:" << c + 1 << " with lines lw 2 title '"
                << (c - 1 < titles.size() ? titles[c - 1] : "") << "'";
        out << "\n";
        if (!out) throw Error(gp + ": write failed");
    }
    const std::string cmd = "gnuplot '" + gp + "' > '" + png + ".log' 2>&1";
    if (std::system(cmd.c_str()) != 0) throw Error("experiment: gnuplot failed on " + gp + " (see " + png + ".log)");
}

}  // namespace trn::experiments
