#include "flight_outputs.hpp"

#include <algorithm>
#include <cmath>
#include <map>
#include <string>

#include "trn/detail/json_number.hpp"
#include "trn/error.hpp"
#include "trn/localize/report.hpp"

namespace trn::experiments {

static_assert(localize::kErrorSlopeBreakS == 35, "the store's slope names say 35s");

double get(const Json& result, const char* key) {
    static const std::map<std::string, std::string> kOldNames{{"filter_error_slope_m_per_km", "filter_slope_m_per_km"},
                                                              {"odometry_error_slope_m_per_km", "odometry_slope_m_per_km"}};
    const auto old = kOldNames.find(key);
    const Json& v = !result.contains(key) && old != kOldNames.end() && result.contains(old->second) ? result.at(old->second) : result.at(key);
    return v.is_null() ? NAN : v.get<double>();
}

std::vector<std::pair<std::string, double>> break_slopes(const localize::LocalizationSummary& s) {
    return {{kFilterSlopeBefore, s.filter_slope_before_break_m_per_s},
            {kFilterSlopeAfter, s.filter_slope_after_break_m_per_s},
            {kOdometrySlopeBefore, s.odometry_slope_before_break_m_per_s},
            {kOdometrySlopeAfter, s.odometry_slope_after_break_m_per_s}};
}

Json flight_result(const localize::LocalizationSummary& s) {
    const auto num = json_number<Json>;
    Json j;
    for (const auto& [key, value] : localize::error_numbers(s)) j[key] = num(value);
    // Fig 3.9's trend lines, broken at 35 s of flight (LocalizationSummary): the store keeps no
    // per-step errors, so the fit is made here, at run time.
    for (const auto& [key, value] : break_slopes(s)) j[key] = num(value);
    j["steps"] = s.steps;
    j["distance_m"] = s.distance_m;
    j["mean_particles"] = s.mean_particles;
    j["reinitialisations"] = s.counters.reinitialisations;
    j["lock_lost_events"] = s.counters.lock_lost_events;
    j["weak_contrast_steps"] = s.counters.weak_contrast_steps;
    j["odometry_inconsistent_steps"] = s.counters.odometry_inconsistent_steps;
    return j;
}

std::vector<double> values_of(const std::vector<Json>& outputs, const char* key, const FlightCell& cell) {
    std::vector<double> values;
    for (const Json& o : outputs) {
        const Json& p = o.at("params");
        const int age = p.value("map_age", 0);  // odometry jobs fly one map and store no age
        if ((!cell.preset.empty() && p.at("preset") != cell.preset) || (!cell.conversion.empty() && p.at("conversion") != cell.conversion) ||
            age < cell.min_age || age > cell.max_age)
            continue;
        const double v = get(o.at("result"), key);
        if (std::isfinite(v)) values.push_back(v);
    }
    return values;
}

double mean_of(const std::vector<Json>& outputs, const char* key, const FlightCell& cell) {
    const std::vector<double> values = values_of(outputs, key, cell);
    double sum = 0;
    for (double v : values) sum += v;
    return values.empty() ? NAN : sum / values.size();
}

double quantile(std::vector<double> v, double q) {
    // Outside 0..1 (or NaN) the order statistic would be read out of range.
    if (!(q >= 0 && q <= 1)) throw Error("quantile: q = " + std::to_string(q) + " is outside 0..1");
    std::erase_if(v, [](double x) { return !std::isfinite(x); });  // a job stores null for a non-finite number
    if (v.empty()) return NAN;
    std::sort(v.begin(), v.end());
    const double at = q * (v.size() - 1);
    const std::size_t below = static_cast<std::size_t>(std::floor(at));
    const std::size_t above = std::min(below + 1, v.size() - 1);
    return v[below] + (at - below) * (v[above] - v[below]);
}

WinCount scenarios_where_more_accurate(const std::vector<Json>& outputs, const std::vector<std::string>& presets, const std::string& better,
                                       const std::string& than) {
    WinCount count;
    for (const auto& p : presets) {
        const double a = mean_of(outputs, "filter_mean_error_m", {p, better}), b = mean_of(outputs, "filter_mean_error_m", {p, than});
        if (std::isnan(a) || std::isnan(b)) continue;
        ++count.scenarios;
        count.wins += a < b;
    }
    return count;
}

double out_of_date_loss_percent(const std::vector<Json>& outputs, const std::string& conversion) {
    const double same_year = mean_of(outputs, "filter_mean_error_m", at_age("", conversion, 0));
    const double other_years = mean_of(outputs, "filter_mean_error_m", {"", conversion, 1});
    return 100 * (other_years / same_year - 1);
}

Table error_spread(const std::vector<Json>& outputs, const std::vector<std::string>& conversions) {
    Table t;
    t.title = "Spread of the flights' mean errors per function: median, mean, 90th percentile, and the share of flights whose mean error "
              "exceeds 50 m and 100 m (lost or late locks; not in the dissertation, which prints means only)";
    t.header = {"Function", "Flights", "Median m", "Mean m", "90th percentile m", "Over 50 m", "Over 100 m"};
    for (const auto& f : conversions) {
        const std::vector<double> e = values_of(outputs, "filter_mean_error_m", {"", f});
        const auto share_over = [&e](double limit) {
            return e.empty() ? NAN : 100.0 * std::count_if(e.begin(), e.end(), [limit](double x) { return x > limit; }) / e.size();
        };
        t.rows.push_back({f, std::to_string(e.size()), fmt(quantile(e, 0.5)), fmt(mean_of(outputs, "filter_mean_error_m", {"", f})),
                          fmt(quantile(e, 0.9)), percent(share_over(50), 1), percent(share_over(100), 1)});
    }
    return t;
}

Table odometry_summary(const std::vector<Json>& outputs, const std::string& study) {
    std::vector<double> filter_final, odometry_final, filter_mean, odometry_mean;
    int final_below = 0, mean_below = 0, within_10 = 0;
    for (const Json& o : outputs) {
        const Json& r = o.at("result");
        const double ff = get(r, "filter_final_error_m"), of = get(r, "odometry_final_error_m");
        const double fm = get(r, "filter_mean_error_m"), om = get(r, "odometry_mean_error_m");
        filter_final.push_back(ff), odometry_final.push_back(of), filter_mean.push_back(fm), odometry_mean.push_back(om);
        final_below += ff < of, mean_below += fm < om, within_10 += ff < 10;
    }
    const std::string of_n = " of " + std::to_string(outputs.size());
    Table t;
    t.title = "The filter against the odometry, " + std::to_string(outputs.size()) + " flights";
    t.header = {"Study", "Final error below odometry's", "Mean error below odometry's", "Median mean error m, filter vs odometry",
                "Median final error m, filter vs odometry", "Final error < 10 m"};
    t.rows.push_back({study, std::to_string(final_below) + of_n, std::to_string(mean_below) + of_n,
                      fmt(quantile(filter_mean, 0.5)) + " vs " + fmt(quantile(odometry_mean, 0.5)),
                      fmt(quantile(filter_final, 0.5)) + " vs " + fmt(quantile(odometry_final, 0.5)),
                      std::to_string(within_10) + of_n});
    return t;
}

Table odometry_break_summary(const std::vector<Json>& outputs, const std::string& study) {
    std::vector<double> fb, fa, ob, oa, ratios;  // ratios: per flight, where the filter's error rises after the break
    int slower = 0, fitted = 0, falling = 0;
    for (const Json& o : outputs) {
        const Json& r = o.at("result");
        if (!r.contains(kFilterSlopeAfter)) continue;  // stored before the broken fit
        ++fitted;
        fb.push_back(get(r, kFilterSlopeBefore)), fa.push_back(get(r, kFilterSlopeAfter));
        ob.push_back(get(r, kOdometrySlopeBefore)), oa.push_back(get(r, kOdometrySlopeAfter));
        slower += fa.back() < oa.back();
        falling += fa.back() <= 0;
        if (fa.back() > 0) ratios.push_back(oa.back() / fa.back());
    }
    const double filter_after = quantile(fa, 0.5), odometry_after = quantile(oa, 0.5);
    Table t;
    t.title = "Fig 3.9's trend lines broken at 35 s of flight: least-squares slopes of the error over time before and after the break, "
              "medians over the flights, m/s; ratio = odometry / filter after the break (diss.: 11x)";
    t.header = {"Study", "Flights with the fit", "Filter before 35 s", "Filter after 35 s", "Odometry before 35 s", "Odometry after 35 s",
                "Filter's error grows slower after 35 s", "Filter's error still falls after 35 s", "Ratio of the medians after 35 s (ours)",
                "Per-flight ratio after 35 s, median (flights whose filter error rises)", "(diss.)"};
    const std::string of_n = " of " + std::to_string(fitted);
    t.rows.push_back({study, std::to_string(fitted) + " of " + std::to_string(outputs.size()), fmt(quantile(fb, 0.5), 3), fmt(filter_after, 3),
                      fmt(quantile(ob, 0.5), 3), fmt(odometry_after, 3), std::to_string(slower) + of_n, std::to_string(falling) + of_n,
                      filter_after > 0 && odometry_after > 0 ? fmt(odometry_after / filter_after) : "n/a",
                      fmt(quantile(ratios, 0.5)) + " (" + std::to_string(ratios.size()) + ")", "11"});
    return t;
}

}  // namespace trn::experiments
