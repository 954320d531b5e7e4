#pragma once
// The dissertation's published numbers for the conversion and robustness studies (Tables 3.7-3.12),
// kept as printed, and which printed table belongs to which conversion family.
//
// The printed Tables 3.7 ("logistic") and 3.8 ("rectifying") carry each other's labels: the column
// means of the printed 3.8 are Table 3.12's logistic accuracies (4 of 5 to the cent) and those of
// the printed 3.7 its rectifying ones, and re-ranking the ten columns reproduces Table 3.9 only
// with the bodies swapped. check_family_labels() computes both; mean_errors() is the swapped reading.
#include <array>
#include <string>
#include <vector>

namespace trn::experiments::diss {

inline constexpr int kScenarios = 12;  // rows, in the order of scenario_names()
inline constexpr int kPerFamily = 5;   // columns: rectifying d = 0.2 .. -0.2, logistic v = 0.7 .. 0.05

using FamilyTable = std::array<std::array<double, kPerFamily>, kScenarios>;

const std::vector<std::string>& scenario_names();     // FL-200 ... UC-300, the tables' row order
const std::vector<std::string>& parametric_functions();  // rectifying:0.2 .. -0.2, logistic:0.7 .. 0.05 (10)

// Bodies as printed, under their printed captions.
extern const FamilyTable kPrintedTable37;  // captioned "logistic"
extern const FamilyTable kPrintedTable38;  // captioned "rectifying"

enum class Family { Rectifying, Logistic };
// The mean errors of a family as the evidence says they belong (logistic: the printed 3.8 body).
const FamilyTable& mean_errors(Family family);
// Published mean error of one parametric function ("logistic:0.2") in scenario `row`.
double mean_error(const std::string& function, int row);

// Table 3.9 in parametric_functions() order: score (sum of ranks) and rank text ("4-5" for a tie).
extern const std::array<int, 10> kTable39Score;
extern const std::array<const char*, 10> kTable39Rank;
// Tables 3.10 (accuracy improvement, %) and 3.11 (speed-up): softmax/linear, logistic 0.2/linear,
// logistic 0.2/softmax per scenario.
extern const std::array<std::array<double, 3>, kScenarios> kTable310, kTable311;
// Table 3.12 in parametric_functions() order: SD (m), mean accuracy (m), RSD (%).
struct RobustnessRow {
    double sd, accuracy, rsd;
};
extern const std::array<RobustnessRow, 10> kTable312;

// Sum over scenarios of each function's rank within its scenario (1 = smallest error), as Table 3.9
// ranks. errors[s][f]: scenario s, function f; a missing value (NaN) ranks last.
std::vector<int> rank_sums(const std::vector<std::vector<double>>& errors);

// How well one assignment of the two printed bodies to the families fits Tables 3.12 and 3.9.
struct LabelFit {
    std::array<double, 10> column_means;  // per function: mean over the 12 scenarios
    double sum_abs_mean_difference;       // vs Table 3.12's accuracy column
    int exact_means;                      // column means equal to Table 3.12's to the cent
    std::vector<int> rank_sums;           // re-ranked as Table 3.9 does
    int max_score_difference;             // vs Table 3.9's scores
};
LabelFit fit_labels(const FamilyTable& rectifying, const FamilyTable& logistic);
struct LabelCheck {
    LabelFit as_printed;  // rectifying = printed 3.8, logistic = printed 3.7
    LabelFit swapped;     // rectifying = printed 3.7, logistic = printed 3.8
};
LabelCheck check_family_labels();

}  // namespace trn::experiments::diss
