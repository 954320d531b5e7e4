#include "table_3_13.hpp"

#include <cmath>

#include "table.hpp"

namespace trn::experiments {
namespace {

// The dissertation's Table 3.13: mean localization error (m) of SVO, DPC-PFL and ORB-SLAM2.
struct Published {
    const char* preset;
    double svo, pfl, orb;
};
constexpr Published kPublished[] = {
    {"FL-200", 48.36, 27.60, 49.56}, {"FL-300", 45.00, 17.08, 58.55}, {"UL-200", 130.95, 21.93, 118.48}, {"UL-300", 129.88, 21.06, 86.05}};

// The dissertation's "relative accuracy": how much smaller the second error is, base / new - 1.
double gain(double base, double better) { return (base / better - 1) * 100; }

}  // namespace

std::string table_3_13(const std::function<double(const std::string&, const char*)>& mean, const std::string& out) {
    Table t;
    t.title = "Table 3.13: mean localization error, DPC-PFL vs visual odometry (ours: our ORB/phase-correlation VO feeds the filter and "
              "is the baseline; diss.: SVO, and ORB-SLAM2, which we do not run)";
    t.header = {"Scenario", "VO m (ours)", "DPC-PFL m (ours)", "PFL/VO (ours)", "SVO m (diss.)", "DPC-PFL m (diss.)", "ORB m (diss.)",
                "PFL/SVO (diss.)", "ORB/SVO (diss.)", "PFL/ORB (diss.)"};
    double ours = 0, pfl_svo = 0, orb_svo = 0, pfl_orb = 0;
    int n = 0;
    for (const Published& p : kPublished) {
        const double vo = mean(p.preset, "odometry_mean_error_m"), pfl = mean(p.preset, "filter_mean_error_m");
        t.rows.push_back({p.preset, fmt(vo), fmt(pfl), percent(gain(vo, pfl)), fmt(p.svo), fmt(p.pfl), fmt(p.orb), percent(gain(p.svo, p.pfl)),
                          percent(gain(p.svo, p.orb)), percent(gain(p.orb, p.pfl))});
        if (std::isfinite(vo) && std::isfinite(pfl)) ours += gain(vo, pfl), ++n;
        pfl_svo += gain(p.svo, p.pfl) / 4, orb_svo += gain(p.svo, p.orb) / 4, pfl_orb += gain(p.orb, p.pfl) / 4;
    }
    t.rows.push_back({"Average", "", "", n ? percent(ours / n) : "n/a", "", "", "", percent(pfl_svo), percent(orb_svo), percent(pfl_orb)});
    t.write(out, "table_3_13");
    return t.markdown();
}

}  // namespace trn::experiments
