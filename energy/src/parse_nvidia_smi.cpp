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

}  // namespace

PowerTrace parse_nvidia_smi(std::string_view input, const std::string& name, const ParseOptions& options) {
    const std::string parser = name + " (nvidia-smi)";
    OptionReader o(options, parser, {"column", "gpu"});
    const auto lines = text::split_lines(input);
    std::size_t hi = 0;
    while (hi < lines.size() && text::trim(lines[hi].text).empty()) ++hi;
    if (hi == lines.size()) throw Error(parser + ": empty file");
    std::vector<std::string> cols;
    for (auto f : text::split(lines[hi].text, ',')) cols.push_back(bare_name(f));
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
    for (std::size_t li = hi + 1; li < lines.size(); ++li) {
        const auto& l = lines[li];
        if (text::trim(l.text).empty()) continue;
        const auto f = text::split(l.text, ',');
        if (f.size() != cols.size()) {
            if (text::trim(l.text) == text::trim(lines[hi].text)) { b.drop(l.number, "repeated header"); continue; }
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
    b.note("time stamps have no time zone (the logging machine's local time); taken as UTC");
    return b.finish();
}

}  // namespace trn::energy
