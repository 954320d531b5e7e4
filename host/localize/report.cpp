#include "trn/localize/report.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <sstream>
#include <nlohmann/json.hpp>
#include <opencv2/imgproc.hpp>

#include "trn/detail/angles.hpp"
#include "trn/error.hpp"
#include "trn/io/atomic_file.hpp"
#include "trn/io/outside_text.hpp"
#include "trn/io/gnuplot.hpp"
#include "trn/io/provenance.hpp"
#include "trn/detail/json_number.hpp"

namespace trn::localize {
namespace {
// A CSV cell: unknown (no ground truth) is an empty cell, never "nan".
struct Cell {
    double v;
};
std::ostream& operator<<(std::ostream& os, Cell c) {
    if (std::isfinite(c.v)) os << c.v;
    return os;
}
// Degrees to 1e-9 (millimetres), empty when the map has no georeference.
struct LatLonCell {
    double v;
};
std::ostream& operator<<(std::ostream& os, LatLonCell c) {
    if (!std::isfinite(c.v)) return os;
    char buf[32];
    std::snprintf(buf, sizeof buf, "%.9f", c.v);
    return os << buf;
}
bool has_errors(const LocalizationSummary& s) { return std::isfinite(s.filter_mean_error_m); }

}  // namespace

void write_rows_csv(const std::string& path, const std::vector<LocalizationRow>& rows, bool heading_columns) {
    io::AtomicFile file(path);
    std::ostream& out = file.stream();
    out.precision(10);
    out << "frame,time_s,distance_m,truth_x,truth_y,odometry_x,odometry_y,estimate_x,estimate_y,estimate_yaw,best_x,best_y,"
           "error_m,odometry_error_m,particles,off_map,score_ms,step_ms,odometry_lost,frame_missing,reinitialised,tilt_deg,too_oblique,"
           "est_lat,est_lon,lock_state,lock_contrast,lock_drift_m,lock_drift_bound_m,lock_lost_events,lock_widen_radius_m,frame_weight,"
           "cov_nn_m2,cov_ne_m2,cov_ee_m2,error_sigmas,odometry_source"
        << (heading_columns ? ",truth_yaw_deg,estimate_yaw_deg,estimate_yaw_sd_deg,yaw_error_deg\n" : "\n");
    std::size_t lost_events = 0;  // running count, so a plot or a grep sees when each loss happened
    for (const LocalizationRow& r : rows) {
        lost_events += r.lock.lost;
        out << r.frame << ',' << r.time_s << ',' << r.distance_m << ',' << Cell{r.truth_x} << ',' << Cell{r.truth_y} << ',' << r.odometry_x << ','
            << r.odometry_y << ',' << r.estimate_x << ',' << r.estimate_y << ',' << r.estimate_yaw << ',' << r.best_x << ',' << r.best_y
            << ',' << Cell{r.error_m} << ',' << Cell{r.odometry_error_m} << ',' << r.particles << ',' << r.off_map << ',' << r.score_ms << ','
            << r.step_ms << ',' << r.odometry_lost << ',' << r.frame_missing << ',' << r.reinitialised << ',' << r.tilt_deg << ','
            << r.too_oblique << ',' << LatLonCell{r.estimate_lat} << ',' << LatLonCell{r.estimate_lon} << ',' << lock_state_name(r.lock) << ','
            << Cell{r.lock.contrast} << ',' << Cell{r.lock.drift_m} << ',' << Cell{r.lock.drift_bound_m} << ',' << lost_events << ','
            << (r.lock.lost ? r.lock.widen_radius_m : 0.0) << ',' << r.frame_weight << ',' << r.cov_nn_m2 << ',' << r.cov_ne_m2 << ',' << r.cov_ee_m2 << ',' << Cell{r.error_sigmas} << ','
            << r.odometry_source;
        if (heading_columns)
            out << ',' << Cell{r.truth_yaw / kDeg} << ',' << r.estimate_yaw / kDeg << ',' << r.estimate_yaw_sd / kDeg << ','
                << Cell{wrap_angle(r.estimate_yaw - r.truth_yaw) / kDeg};
        out << '\n';
    }
    file.commit();
}

std::vector<std::pair<std::string, double>> error_numbers(const LocalizationSummary& s) {
    return {{"filter_mean_error_m", s.filter_mean_error_m},
            {"odometry_mean_error_m", s.odometry_mean_error_m},
            {"filter_final_error_m", s.filter_final_error_m},
            {"odometry_final_error_m", s.odometry_final_error_m},
            {"filter_error_slope_m_per_km", s.filter_error_slope_m_per_km},
            {"odometry_error_slope_m_per_km", s.odometry_error_slope_m_per_km}};
}

std::vector<std::pair<std::string, double>> heading_numbers(const LocalizationSummary& s) {
    return {{"mean_yaw_error_deg", s.mean_yaw_error_deg},
            {"final_yaw_error_deg", s.final_yaw_error_deg},
            {"final_yaw_sd_deg", s.final_yaw_sd_deg},
            {"converged_yaw_sd_deg", kConvergedYawSdDeg},
            {"converged_from_frame", s.converged_from_frame},
            {"converged_mean_error_m", s.converged_mean_error_m},
            {"converged_mean_yaw_error_deg", s.converged_mean_yaw_error_deg}};
}

void write_summary_json(const std::string& path, const LocalizationSummary& s, const std::map<std::string, std::string>& strings,
                        const std::map<std::string, double>& numbers) {
    nlohmann::ordered_json j;
    const auto num = json_number<nlohmann::ordered_json>;
    j["ground_truth"] = has_errors(s);
    if (has_errors(s)) {
        for (const auto& [key, value] : error_numbers(s)) j[key] = num(value);
        j["truth_inside_1sigma"] = num(s.inside_1sigma);  // the covariance's calibration (LocalizationSummary)
        j["truth_inside_2sigma"] = num(s.inside_2sigma);
    } else {
        j["errors"] = "no ground truth: the flight has no MapX/MapY, so no error is computed";
    }
    j["mean_particles"] = num(s.mean_particles);
    j["frames_per_second"] = num(s.frames_per_second);
    j["mean_score_ms"] = num(s.mean_score_ms);
    j["steps"] = s.steps;
    if (has_errors(s)) j["distance_m"] = num(s.distance_m);  // flown along the ground truth: unknown without it
    j["odometry_lost"] = s.counters.odometry_lost;
    j["frames_missing"] = s.counters.frames_missing;
    j["frames_too_oblique"] = s.frames_too_oblique;
    j["particles_off_map"] = s.counters.particles_off_map;
    j["reinitialisations"] = s.counters.reinitialisations;
    io::add_provenance(j);  // what produced these numbers
    for (const auto& [k, v] : strings) j[k] = v;
    for (const auto& [k, v] : numbers) j[k] = num(v);
    io::write_file_atomic(path, io::json_text(j, 2));
}

std::string format_summary(const LocalizationSummary& s) {
    char buf[1024];
    // Only when it happened: level flights keep their usual summary.
    const std::string oblique = s.frames_too_oblique ? "skipped:      " + std::to_string(s.frames_too_oblique) + " frames too oblique to score\n" : "";
    if (!has_errors(s)) {
        std::snprintf(buf, sizeof buf,
                      "steps %zu\n"
                      "no ground truth: errors not computed\n"
                      "particles:    mean %.1f   filter speed %.1f frames/s (mean scoring %.2f ms)\n"
                      "handled:      %zu odometry lost, %zu frames missing, %zu off-map particle scores, %zu re-initialisations\n",
                      s.steps, s.mean_particles, s.frames_per_second, s.mean_score_ms, s.counters.odometry_lost, s.counters.frames_missing,
                      s.counters.particles_off_map, s.counters.reinitialisations);
        return buf + oblique;
    }
    std::snprintf(buf, sizeof buf,
                  "steps %zu over %.2f km\n"
                  "mean error:   filter %8.2f m   odometry %8.2f m   (ratio %.3f)\n"
                  "final error:  filter %8.2f m   odometry %8.2f m\n"
                  "error slope:  filter %8.2f m/km odometry %8.2f m/km (ratio %.3f)\n"
                  "particles:    mean %.1f   filter speed %.1f frames/s (mean scoring %.2f ms)\n"
                  "handled:      %zu odometry lost, %zu frames missing, %zu off-map particle scores, %zu re-initialisations\n"
                  "uncertainty:  truth inside the 1-sigma ellipse %.0f %%, 2-sigma %.0f %% (a Gaussian: 39 %%, 86 %%)\n",
                  s.steps, s.distance_m / 1000, s.filter_mean_error_m, s.odometry_mean_error_m, s.filter_mean_error_m / s.odometry_mean_error_m,
                  s.filter_final_error_m, s.odometry_final_error_m, s.filter_error_slope_m_per_km, s.odometry_error_slope_m_per_km,
                  s.filter_error_slope_m_per_km / s.odometry_error_slope_m_per_km, s.mean_particles, s.frames_per_second, s.mean_score_ms,
                  s.counters.odometry_lost, s.counters.frames_missing, s.counters.particles_off_map, s.counters.reinitialisations,
                  100 * s.inside_1sigma, 100 * s.inside_2sigma);
    return buf + oblique;
}

// A number as gnuplot reads it; NaN (too few points for a line) as gnuplot's NaN.
std::string gp_number(double v) {
    if (!std::isfinite(v)) return "NaN";
    std::ostringstream os;
    os.precision(10);
    os << v;
    return os.str();
}

PlotFiles plot_run(const std::string& folder, const std::vector<LocalizationRow>& rows, const LocalizationSummary& s, GrayView map,
                   double mpp, const std::string& title, const ReferenceTrack& reference, const std::string& odometry_title) {
    // gnuplot runs in `folder` and the script names only these fixed files; the title (from a
    // flight.json or an option) enters only as a gnuplot_string.
    const std::string raw = "map_plot.gray", data = "plot_data.tsv";
    const io::PlotTarget trajectory{folder, "trajectory.png", folder + "/trajectory.png"};
    const io::PlotTarget error{folder, "error.png", folder + "/error.png"};
    using io::gnuplot_string;
    // The map as raw 8-bit pixels, at most 1000 px wide, in metres on the axes.
    const double factor = std::max(1.0, std::max(map.width, map.height) / 1000.0);
    const int w = std::max(1, static_cast<int>(map.width / factor)), h = std::max(1, static_cast<int>(map.height / factor));
    std::string small(std::size_t(w) * h, '\0');
    const cv::Mat src(map.height, map.width, CV_8UC1, const_cast<std::uint8_t*>(map.data), std::size_t(map.stride));
    cv::Mat dst(h, w, CV_8UC1, small.data());
    cv::resize(src, dst, dst.size(), 0, 0, cv::INTER_AREA);
    std::ostringstream table;
    table.precision(10);
    const bool has_reference = !reference.px.empty();
    if (has_reference && reference.px.size() != rows.size())
        throw Error("reference track '" + reference.title + "': " + std::to_string(reference.px.size()) + " points for " +
                    std::to_string(rows.size()) + " rows");
    for (std::size_t i = 0; i < rows.size(); ++i) {
        const LocalizationRow& r = rows[i];
        table << r.distance_m / 1000 << '\t' << r.truth_x * mpp << '\t' << r.truth_y * mpp << '\t' << r.odometry_x * mpp << '\t'
              << r.odometry_y * mpp << '\t' << r.estimate_x * mpp << '\t' << r.estimate_y * mpp << '\t' << r.error_m << '\t'
              << r.odometry_error_m;
        if (has_reference) table << '\t' << gp_number(reference.px[i][0] * mpp) << '\t' << gp_number(reference.px[i][1] * mpp);
        table << '\n';
    }

    std::ostringstream gp;
    const double px_m = factor * mpp;
    const bool truth = has_errors(s);
    // Trajectories: zoom on the flown area plus a margin.
    double x0 = 1e300, x1 = -1e300, y0 = 1e300, y1 = -1e300;
    for (const LocalizationRow& r : rows)
        for (auto [x, y] : {std::pair{r.truth_x, r.truth_y}, std::pair{r.odometry_x, r.odometry_y}, std::pair{r.estimate_x, r.estimate_y}})
            if (std::isfinite(x) && std::isfinite(y)) x0 = std::min(x0, x * mpp), x1 = std::max(x1, x * mpp), y0 = std::min(y0, y * mpp), y1 = std::max(y1, y * mpp);
    for (const auto& [x, y] : reference.px)
        if (std::isfinite(x) && std::isfinite(y)) x0 = std::min(x0, x * mpp), x1 = std::max(x1, x * mpp), y0 = std::min(y0, y * mpp), y1 = std::max(y1, y * mpp);
    const double margin = 50;
    gp << io::gnuplot_png_terminal(1100, 1000, "sans,11") << "set output " << gnuplot_string(trajectory.name) << "\n"
       << "set title " << gnuplot_string(title + ": trajectories on the map") << "\n"
       << "set xlabel 'east (m)'\nset ylabel 'south (m)'\nset size ratio -1\nunset colorbox\n"
       << "set palette gray\nset key opaque box\n"
       << "set xrange [" << x0 - margin << ":" << x1 + margin << "]\n"
       << "set yrange [" << y1 + margin << ":" << y0 - margin << "]\n"
       << "plot " << gnuplot_string(raw) << " binary array=(" << w << "," << h << ") format='%uchar' dx=" << px_m << " dy=" << px_m
       << " origin=(0,0) flipy with image notitle, \\\n"
       << "  " << gnuplot_string(data) << (truth ? " using 2:3 with lines lw 3 lc rgb '#1a9850' title 'ground truth', \\\n  ''" : "")
       << " using 4:5 with lines lw 2 lc rgb '#d73027' title " << gnuplot_string(odometry_title) << ", \\\n"
       << "  '' using 6:7 with lines lw 2 lc rgb '#4575b4' title 'DPC-PFL estimate'"
       << (has_reference ? ", \\\n  '' using 10:11 with points pt 7 ps 1.2 lc rgb '#fdae61' title " + gnuplot_string(reference.title) : std::string())
       << "\n";
    if (!truth) {  // no ground truth, no errors: the trajectories only
        io::run_gnuplot({folder, "plot.gp", gp.str(), {{raw, small}, {data, table.str()}}, "gnuplot.log", {trajectory}});
        return {trajectory.path, ""};
    }
    gp << io::gnuplot_png_terminal(1100, 600, "sans,11") << "set output " << gnuplot_string(error.name) << "\n"
       << "reset\nset title " << gnuplot_string(title + ": position error over distance flown") << "\n"
       << "set xlabel 'distance flown (km)'\nset ylabel 'error (m)'\nset grid\nset key left top\n"
       // The trend lines are the summary's own least-squares fits (gnuplot's `fit` would
       // compute them a second time and leave a fit.log in the working directory).
       << "ao = " << gp_number(s.odometry_error_slope_m_per_km) << "\nbo = " << gp_number(s.odometry_error_intercept_m) << "\n"
       << "af = " << gp_number(s.filter_error_slope_m_per_km) << "\nbf = " << gp_number(s.filter_error_intercept_m) << "\n"
       << "fo(x) = ao*x + bo\nff(x) = af*x + bf\n"
       << "plot " << gnuplot_string(data) << " using 1:9 with lines lw 2 lc rgb '#d73027' title " << gnuplot_string(odometry_title) << ", \\\n"
       << "  '' using 1:8 with lines lw 2 lc rgb '#4575b4' title 'DPC-PFL', \\\n"
       << "  fo(x) with lines dt 2 lw 2 lc rgb '#d73027' title sprintf('odometry trend %.1f m/km', ao), \\\n"
       << "  ff(x) with lines dt 2 lw 2 lc rgb '#4575b4' title sprintf('filter trend %.1f m/km', af)\n";
    io::run_gnuplot({folder, "plot.gp", gp.str(), {{raw, small}, {data, table.str()}}, "gnuplot.log", {trajectory, error}});
    return {trajectory.path, error.path};
}

}  // namespace trn::localize
