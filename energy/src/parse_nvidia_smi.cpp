// nvidia-smi --query-gpu=... --format=csv[,nounits] logs.
#include <algorithm>
#include <cmath>
#include <set>

#include "option_reader.hpp"
#include "trace_builder.hpp"
#include "trn/energy/parsers.hpp"

namespace trn::energy {
namespace {

// "power.draw [W]" -> "power.draw"
std::string bare_name(std::string_view column) {
    column = text::trim(column);
    if (const auto b = column.find(" ["); b != std::string_view::npos) column = column.substr(0, b);
    return text::lower(column);
}

// Column names for a --format=csv,noheader log: from columns=..., else guessed from the first
// row (a YYYY/MM/DD time stamp, a whole number before it = index, the one field in W = power).
std::vector<std::string> headerless_columns(std::string_view row, const std::string& name, std::size_t line, const OptionReader& o) {
    std::vector<std::string> cols;
    if (const auto given = o.text("columns")) {
        for (auto f : text::split(*given, ',')) cols.push_back(bare_name(f));
        return cols;
    }
    const auto f = text::split(row, ',');
    int ts = -1;
    std::vector<int> watts, numbers;
    for (std::size_t i = 0; i < f.size(); ++i) {
        const std::string_view v = text::trim(f[i]);
        if (ts < 0 && text::parse_datetime(v)) ts = static_cast<int>(i);
        else if (v.size() > 2 && v.substr(v.size() - 2) == " W" && text::to_number(v.substr(0, v.size() - 2))) watts.push_back(static_cast<int>(i));
        else if (text::to_number(v)) numbers.push_back(static_cast<int>(i));
    }
    if (ts < 0) text::fail(name, line, "no header and no YYYY/MM/DD HH:MM:SS time stamp in the first row; pass columns=timestamp,power.draw,...");
    const bool index_first = ts == 1 && !numbers.empty() && numbers.front() == 0;
    if (index_first) numbers.erase(numbers.begin());
    int power = -1;
    if (watts.size() == 1) power = watts.front();
    else if (watts.empty() && numbers.size() == 1) power = numbers.front();
    if (power < 0)
        text::fail(name, line, "no header, and the power field cannot be told from the others (" + std::to_string(watts.size() + numbers.size()) +
                                   " candidates); pass columns=NAME,... as given to --query-gpu");
    cols.assign(f.size(), "");
    for (std::size_t i = 0; i < f.size(); ++i) cols[i] = "field" + std::to_string(i + 1);
    cols[ts] = "timestamp";
    cols[power] = "power.draw";
    if (index_first) cols[0] = "index";
    return cols;
}

}  // namespace

PowerTrace parse_nvidia_smi(std::string_view input, const std::string& name, const ParseOptions& options) {
    const std::string parser = name + " (nvidia-smi)";
    OptionReader o(options, parser, {"column", "gpu", "columns"});
    const auto lines = text::split_lines(input);
    std::size_t hi = 0;
    while (hi < lines.size() && text::trim(lines[hi].text).empty()) ++hi;
    if (hi == lines.size()) throw Error(parser + ": empty file");
    std::vector<std::string> cols;
    for (auto f : text::split(lines[hi].text, ',')) cols.push_back(bare_name(f));
    // --format=csv,noheader: the first line is already a row (it has no 'timestamp' name).
    const bool headerless = o.text("columns") || std::find(cols.begin(), cols.end(), "timestamp") == cols.end();
    std::size_t first_row = hi + 1;
    if (headerless) {
        cols = headerless_columns(lines[hi].text, name, lines[hi].number, o);
        first_row = hi;
    }
    auto col = [&](const std::string& n) {
        const auto it = std::find(cols.begin(), cols.end(), n);
        return it == cols.end() ? -1 : static_cast<int>(it - cols.begin());
    };
    const int ct = col("timestamp");
    if (ct < 0) text::fail(name, lines[hi].number, "header has no 'timestamp' column (use --query-gpu=timestamp,power.draw,...)");
    std::string power_name = o.text("column", col("power.draw.instant") >= 0 ? "power.draw.instant" : "power.draw");
    const int cp = col(power_name);
    if (cp < 0) text::fail(name, lines[hi].number, "header has no '" + power_name + "' column");
    int cid = col("index");
    if (cid < 0) cid = col("uuid");
    if (cid < 0) cid = col("pci.bus_id");
    const auto gpu = o.text("gpu");
    if (gpu && cid < 0) throw Error(parser + ": gpu=" + *gpu + " given but the log has no index, uuid or pci.bus_id column");

    struct Row { std::size_t line; double t; double w; std::string id; };
    std::vector<Row> rows;
    TraceBuilder b(name, "nvidia-smi");
    b.trace().quantity = power_name + (power_name == "power.draw" ? " (the driver's power reading; on recent drivers a 1 s average)" : "");
    b.trace().wall_clock = true;
    b.trace().resolution_w = 0.01;
    std::set<std::string> ids;
    for (std::size_t li = first_row; li < lines.size(); ++li) {
        const auto& l = lines[li];
        if (text::trim(l.text).empty()) continue;
        const auto f = text::split(l.text, ',');
        if (f.size() != cols.size()) {
            if (!headerless && text::trim(l.text) == text::trim(lines[hi].text)) { b.drop(l.number, "repeated header"); continue; }
            text::fail(name, l.number, "expected " + std::to_string(cols.size()) + " fields as in the header, found " + std::to_string(f.size()));
        }
        const auto t = text::parse_datetime(f[ct]);
        if (!t) text::fail(name, l.number, "timestamp '" + std::string(text::trim(f[ct])) + "' is not YYYY/MM/DD HH:MM:SS.mmm");
        std::string_view pv = text::trim(f[cp]);
        if (pv.size() > 2 && pv.substr(pv.size() - 2) == " W") pv.remove_suffix(2);
        const auto w = text::to_number(pv);
        if (!w) {
            b.drop(l.number, "power not available ('" + std::string(text::trim(f[cp])).substr(0, 20) + "')");
            continue;
        }
        const std::string id = cid >= 0 ? std::string(text::trim(f[cid])) : "";
        ids.insert(id);
        rows.push_back({l.number, *t, *w, id});
    }
    if (cid >= 0 && ids.size() > 1 && !gpu) {
        std::string list;
        for (const auto& i : ids) list += (list.empty() ? "" : ", ") + i;
        throw Error(parser + ": " + std::to_string(ids.size()) + " GPUs in the log (" + list + "); pass gpu=ONE_OF_THEM");
    }
    if (cid < 0 && rows.size() >= 8) {
        // Several GPUs logged without an id column come as bursts of rows per tick: then many
        // intervals are far shorter than the typical one and rows cannot be told apart.
        std::vector<double> dt;
        for (std::size_t i = 1; i < rows.size(); ++i) dt.push_back(rows[i].t - rows[i - 1].t);
        std::vector<double> sorted = dt;
        std::sort(sorted.begin(), sorted.end());
        const double q75 = sorted[sorted.size() * 3 / 4];
        std::size_t short_count = 0, first_short = 0;
        for (std::size_t i = 0; i < dt.size(); ++i)
            if (dt[i] < q75 / 4 && short_count++ == 0) first_short = rows[i + 1].line;
        if (short_count * 10 >= dt.size() * 3)
            text::fail(name, first_short, "rows come in bursts (" + std::to_string(short_count) + " of " + std::to_string(dt.size()) +
                                              " intervals < 1/4 of the usual): several GPUs logged without an index/uuid column cannot be told apart; add index to --query-gpu");
    }
    for (const Row& r : rows) {
        if (gpu && r.id != *gpu) continue;
        b.add(r.line, r.t, r.w);
    }
    b.trace().local_time = true;
    b.note("time stamps have no time zone (the logging machine's local time); taken as UTC (--timezone/--utc-offset to convert)");
    return b.finish();
}

}  // namespace trn::energy
