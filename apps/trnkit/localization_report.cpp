#include "localization_report.hpp"

#include <cmath>

#include "trn/filter/report.hpp"
#include "trn/io/output_folder.hpp"

namespace trn::cli {

void report_localization(const filter::LocalizationResult& result, const Backend& backend, const filter::FilterConfig& cfg,
                         GrayView map, double metres_per_pixel, const LocalizationReport& r, std::ostream& os) {
    // The fields every run records; the command's own come on top (and may refine these).
    std::map<std::string, std::string> strings{{"backend", backend.info().name},
                                               {"device", backend.info().device},
                                               {"conversion", cfg.conversion.to_string()},
                                               {"sampling", filter::to_string(cfg.sampling)},
                                               {"scoring_density", r.sparse < 1 ? "random " + std::to_string(r.sparse) : "dense"}};
    for (const auto& [k, v] : r.strings) strings[k] = v;
    std::map<std::string, double> numbers{{"seed", static_cast<double>(r.seed)},
                                          {"filter_rate_hz", r.filter_rate_hz},
                                          {"template_width", static_cast<double>(r.template_width)}};
    for (const auto& [k, v] : r.numbers) numbers[k] = v;
    numbers = filter::with_lock_numbers(result.summary, std::move(numbers));
    std::erase_if(numbers, [](const auto& kv) { return std::isnan(kv.second); });  // options not given

    // One run's files: the previous run's are removed first (a failed rerun never leaves new
    // results beside old plots), and a second run into the folder waits for this one.
    io::open_output_folder(r.out, r.command, r.force, "--out", io::Rerun::ReplacesPrevious);
    filter::write_rows_csv(r.out + "/localization.csv", result.rows);
    filter::write_summary_json(r.out + "/summary.json", result.summary, strings, numbers);
    os << filter::format_summary(result.summary) << filter::format_lock_summary(result.summary) << r.after_summary << "summary JSON: " << r.out
       << "/summary.json\nper-step CSV: " << r.out << "/localization.csv\n";
    if (r.plots) {
        const filter::PlotFiles plots = filter::plot_run(r.out, result.rows, result.summary, map, metres_per_pixel, r.plot_title);
        os << "plots: " << plots.trajectory_png << "\n";
        if (!plots.error_png.empty()) os << "       " << plots.error_png << "\n";  // none without ground truth
    }
}

}  // namespace trn::cli
