#include "trn/localize/report_folder.hpp"

#include <cmath>
#include <cstdio>

#include "trn/error.hpp"
#include "trn/io/atomic_file.hpp"
#include "trn/io/output_folder.hpp"
#include "trn/localize/report.hpp"

namespace trn::localize {

void write_localization_report(const LocalizationResult& result, const std::string& folder, GrayView map, double metres_per_pixel,
                               const ReportOptions& r, std::ostream& os) {
    const RunInfo& run = result.run;
    // The fields every run records; the caller's own come on top (and may refine these).
    std::map<std::string, std::string> strings{{"backend", run.backend},
                                               {"device", run.device},
                                               {"conversion", run.conversion},
                                               {"sampling", run.sampling},
                                               {"scoring_density", run.sparse < 1 ? "random " + std::to_string(run.sparse) : "dense"},
                                               {"odometry", r.odometry}};
    std::map<std::string, double> numbers{{"seed", static_cast<double>(run.seed)},
                                          {"filter_rate_hz", run.filter_rate_hz},
                                          {"template_width", static_cast<double>(run.template_width)}};
    std::string after_summary = r.after_summary;
    if (run.visual_odometry) {
        strings["odometry"] = "visual (ORB + RANSAC similarity frame to frame, phase-correlation fallback)";
        const auto& c = run.visual_odometry_counts;
        numbers["visual_odometry_feature_steps"] = static_cast<double>(c.features);
        numbers["visual_odometry_phase_steps"] = static_cast<double>(c.phase);
        numbers["visual_odometry_lost_steps"] = static_cast<double>(c.lost);
        numbers["visual_odometry_no_frame_steps"] = static_cast<double>(c.no_frame);
        char line[200];
        std::snprintf(line, sizeof line, "visual odometry: %zu steps by features, %zu by phase correlation, %zu lost, %zu without a frame\n",
                      c.features, c.phase, c.lost, c.no_frame);
        after_summary += line;
    }
    for (const auto& [k, v] : r.strings) strings[k] = v;
    for (const auto& [k, v] : r.numbers) numbers[k] = v;
    numbers = with_lock_numbers(result.summary, std::move(numbers));
    std::erase_if(numbers, [](const auto& kv) { return std::isnan(kv.second); });  // options not given
    const bool compassless = run.heading == "none";
    if (compassless) {  // the heading is an output: its figures, null when unknown (no truth, never converged)
        strings["heading"] = "none (compass-less: yaw estimated, turned by the odometry's rotation)";
        for (const auto& [k, v] : heading_numbers(result.summary)) numbers[k] = v;
        char line[240], since[96] = "not converged";
        if (!std::isnan(result.summary.converged_from_frame))
            std::snprintf(since, sizeof since, "from frame %.0f, mean error since %.2f m", result.summary.converged_from_frame,
                          result.summary.converged_mean_error_m);
        std::snprintf(line, sizeof line, "heading:      none; final yaw sd %.1f deg, mean yaw error %.1f deg; converged (yaw sd < %.0f deg and a lock fix): %s\n",
                      result.summary.final_yaw_sd_deg, result.summary.mean_yaw_error_deg, kConvergedYawSdDeg, since);
        after_summary = line + after_summary;
    }

    // One run's files: the previous run's are removed first (a failed rerun never leaves new
    // results beside old plots), and a second run into the folder waits for this one.
    io::open_output_folder(folder, r.owner, r.force, r.folder_name, io::Rerun::ReplacesPrevious);
    write_rows_csv(folder + "/localization.csv", result.rows, compassless);
    write_summary_json(folder + "/summary.json", result.summary, strings, numbers);
    for (const auto& [name, text] : r.files) {
        if (name.empty() || name.find('/') != std::string::npos || name[0] == '.') throw Error("report file name '" + name + "' is not a plain name");
        io::write_file_atomic(folder + "/" + name, text, io::Destination::Derived);
    }
    os << format_summary(result.summary) << format_lock_summary(result.summary) << after_summary << "summary JSON: " << folder
       << "/summary.json\nper-step CSV: " << folder << "/localization.csv\n";
    for (const auto& [name, text] : r.files) os << name << ": " << folder << "/" << name << "\n";
    if (r.plots) {
        const std::string odometry = result.run.visual_odometry ? "visual odometry" : "odometry (" + r.odometry + ")";
        const PlotFiles plots = plot_run(folder, result.rows, result.summary, map, metres_per_pixel, r.plot_title, r.reference, odometry);
        os << "plots: " << plots.trajectory_png << "\n";
        if (!plots.error_png.empty()) os << "       " << plots.error_png << "\n";  // none without ground truth
    }
}

}  // namespace trn::localize
