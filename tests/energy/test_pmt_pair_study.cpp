// The dissertation's energy method end to end on real logs (issue 46 item 5): the shared PMT pair
// (an RTX 4000 Ada through NVML, a Radeon Pro W7700 through ROCm SMI, each dump with four
// start/end marked windows) through `trnkit energy integrate` and `energy compare`, once with the
// dissertation's settings (gross energy, Student's t, every marked iteration a value,
// Shapiro-Wilk) and once with ours (net energy, Welch). No figure is written into the test: each
// is checked against what the test computes itself from the same inputs (the log's samples by
// its own trapezoid sum, the t statistics from the reports' per-frame joules).
#include <gtest/gtest.h>

#include <unistd.h>

#include <boost/math/distributions/students_t.hpp>
#include <cmath>
#include <iostream>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>
#include <vector>

#include "../cli/cli_process.hpp"
#include "../common/shared_data.hpp"

namespace {
namespace fs = std::filesystem;
using nlohmann::json;

struct PmtLog {
    std::string file, platform, column;  // the column a reader of that sensor integrates
};
const PmtLog kNvml{"nlesc_ps3results_rtx4000ada_pmt-nvml.log", "rtx4000ada-nvml", "gpu_instant"};
const PmtLog kRocm{"nlesc_ps3results_w7700_pmt-rocm.log", "w7700-rocm", "device"};

fs::path pmt_folder() {
    return trn::test::shared_data("powerlogs/pmt");
}

json read_json(const fs::path& p) {
    std::ifstream f(p);
    return json::parse(f);
}

// The log's samples as the test reads them: the header names the columns, "M ..." lines are
// markers, every other line is "timestamp value...".
std::vector<std::pair<double, double>> samples(const fs::path& log, const std::string& column) {
    std::ifstream in(log);
    std::string line, name;
    std::getline(in, line);
    std::istringstream header(line);
    std::size_t col = 0, i = 0;
    while (header >> name) {
        if (name == column) col = i;
        ++i;
    }
    EXPECT_GT(col, 0u) << "column " << column << " not in " << log;
    std::vector<std::pair<double, double>> out;
    while (std::getline(in, line)) {
        if (line.empty() || line[0] == 'M') continue;
        std::istringstream row(line);
        std::vector<double> v;
        double x = 0;
        while (row >> x) v.push_back(x);
        out.emplace_back(v.at(0), v.at(col));
    }
    return out;
}

// Joules over [a, b] with the power linear between samples (the trapezoid rule).
double trapezoid(const std::vector<std::pair<double, double>>& s, double a, double b) {
    double e = 0;
    for (std::size_t k = 0; k + 1 < s.size(); ++k) {
        // (Plain names, not structured bindings: a lambda may capture those only from Clang 16.)
        const double t0 = s[k].first, w0 = s[k].second, t1 = s[k + 1].first, w1 = s[k + 1].second;
        const double x = std::max(a, t0), y = std::min(b, t1);
        if (y <= x) continue;
        const auto at = [&](double t) { return w0 + (w1 - w0) * (t - t0) / (t1 - t0); };
        e += (y - x) * (at(x) + at(y)) / 2;
    }
    return e;
}

struct Values {
    double mean = 0, var = 0;
    std::size_t n = 0;
};
Values values(const std::vector<double>& v) {
    Values r;
    r.n = v.size();
    for (double x : v) r.mean += x / static_cast<double>(r.n);
    for (double x : v) r.var += (x - r.mean) * (x - r.mean) / static_cast<double>(r.n - 1);
    return r;
}

class PmtPairStudy : public ::testing::Test {
protected:
    static inline fs::path dir;
    static inline std::string setup_error;
    static inline bool present = false;

    static void SetUpTestSuite() {
        const fs::path pmt = pmt_folder();
        present = !pmt.empty() && fs::exists(pmt / kNvml.file) && fs::exists(pmt / kRocm.file);
        if (!present) return;
        dir = fs::temp_directory_path() / ("trn_pmt_pair_" + std::to_string(::getpid()));
        fs::remove_all(dir);
        fs::create_directories(dir);
        for (const auto& log : {kNvml, kRocm}) {
            const std::string cmd = "energy integrate " + (pmt / log.file).string() + " --platform " + log.platform + " --json " +
                                    (dir / (log.platform + ".json")).string() + " --csv " + (dir / (log.platform + ".csv")).string();
            const auto r = trn::test::run_trnkit(cmd);
            if (r.code != 0) setup_error += cmd + "\n" + r.output;
        }
    }
    static void TearDownTestSuite() {
        if (!dir.empty()) fs::remove_all(dir);
    }
    void SetUp() override {
        if (!present) GTEST_SKIP() << "TRN_SHARED_DATA/powerlogs/pmt not found: the shared PMT pair is unavailable, nothing was checked";
        ASSERT_TRUE(setup_error.empty()) << setup_error;
    }
    static std::string reports() { return (dir / (kNvml.platform + ".json")).string() + " " + (dir / (kRocm.platform + ".json")).string(); }
    // Per-frame energies (mJ) of the usable frames of one report.
    static std::vector<double> frame_mj(const std::string& platform, const char* which) {
        std::vector<double> v;
        const json report = read_json(dir / (platform + ".json"));
        for (const auto& f : report["frames"])
            if (f["flag"].get<std::string>().empty()) v.push_back(f[which].get<double>() * 1000);
        return v;
    }
};

TEST_F(PmtPairStudy, IntegrateMatchesAnIndependentTrapezoidOfTheLog) {
    for (const auto& log : {kNvml, kRocm}) {
        SCOPED_TRACE(log.file);
        const json r = read_json(dir / (log.platform + ".json"));
        EXPECT_EQ(r["platform"], log.platform);
        EXPECT_EQ(r["inputs"]["log"]["format"], "pmt");
        const auto s = samples(pmt_folder() / log.file, log.column);
        ASSERT_EQ(r["frames"].size(), 4u) << "the dump marks four start/end windows";
        const double idle_w = r["idle"]["w"];
        EXPECT_GT(idle_w, 0);
        for (const auto& f : r["frames"]) {
            const double a = f["start_s"], b = f["end_s"], gross = f["gross_j"], net = f["net_j"];
            EXPECT_EQ(f["flag"], "");
            ASSERT_GT(b, a);
            EXPECT_NEAR(gross, trapezoid(s, a, b), 1e-9 * gross) << "frame " << f["id"];
            EXPECT_NEAR(net, gross - idle_w * (b - a), 1e-9 * gross) << "net = gross - idle W x duration";
            EXPECT_GT(gross / (b - a), idle_w) << "a marked window draws more than the idle gaps";
        }
    }
}

// Each figure of a comparison from the reports' frames: n and mean per platform, the t statistic
// and its degrees of freedom, the two-sided p, and the verdicts (normality, difference) from them.
void check_comparison(const fs::path& out, const std::string& stdout_text, const std::map<std::string, std::vector<double>>& frames,
                      const std::string& test) {
    const json j = read_json(out / "summary.json");
    EXPECT_EQ(j["config"]["unit"], "frames");
    const double alpha = j["config"]["alpha"];
    ASSERT_EQ(j["platforms"].size(), 2u);
    for (const auto& p : j["platforms"]) {
        const auto& v = frames.at(p["name"]);
        EXPECT_EQ(p["energy_mj"]["n"], v.size());
        EXPECT_NEAR(p["energy_mj"]["mean"].get<double>(), values(v).mean, 1e-9 * values(v).mean);
        const auto& sw = p["shapiro_wilk"];
        ASSERT_TRUE(sw.contains("p")) << sw.dump();
        const bool rejected = sw["p"].get<double>() < alpha;
        EXPECT_EQ(sw["rejected"], rejected);
        EXPECT_NE(stdout_text.find(p["name"].get<std::string>() + ":"), std::string::npos);
        EXPECT_NE(stdout_text.find(rejected ? "normality REJECTED" : "normality not rejected"), std::string::npos) << stdout_text;
    }
    ASSERT_EQ(j["pairs"].size(), 1u);
    const auto& pair = j["pairs"][0];
    const Values a = values(frames.at(pair["a"])), b = values(frames.at(pair["b"]));
    double t = 0, df = 0;
    if (test == "student") {
        df = static_cast<double>(a.n + b.n - 2);
        const double pooled = ((a.n - 1) * a.var + (b.n - 1) * b.var) / df;
        t = (a.mean - b.mean) / std::sqrt(pooled * (1.0 / a.n + 1.0 / b.n));
    } else {
        const double va = a.var / a.n, vb = b.var / b.n;
        t = (a.mean - b.mean) / std::sqrt(va + vb);
        df = (va + vb) * (va + vb) / (va * va / (a.n - 1) + vb * vb / (b.n - 1));
    }
    ASSERT_EQ(pair["t_tests"].size(), 1u);
    const auto& tt = pair["t_tests"][0];
    EXPECT_EQ(tt["test"], test);
    EXPECT_NEAR(tt["t"].get<double>(), t, 1e-9 * std::abs(t));
    EXPECT_NEAR(tt["df"].get<double>(), df, 1e-9 * df);
    const double p = 2 * boost::math::cdf(boost::math::students_t(df), -std::abs(t));
    EXPECT_NEAR(tt["p"].get<double>(), p, 1e-9 + 1e-6 * p);
    EXPECT_DOUBLE_EQ(tt["p_holm"].get<double>(), tt["p"].get<double>()) << "one pair: Holm leaves p as it is";
    EXPECT_NEAR(pair["ratio"].get<double>(), a.mean / b.mean, 1e-9 * a.mean / b.mean);
    // The verdict a reader takes from Table 3 is the one the p gives.
    const std::string title = test == "student" ? "Student" : "Welch";
    EXPECT_NE(stdout_text.find(title + " p(Holm) = "), std::string::npos) << stdout_text;
    std::ifstream tables(out / "tables.md");
    std::string row, line;
    const std::string start = "| " + pair["a"].get<std::string>() + " | " + pair["b"].get<std::string>() + " | " + title + " |";
    while (std::getline(tables, line))
        if (line.rfind(start, 0) == 0) row = line;
    ASSERT_FALSE(row.empty()) << "no Table 3 row " << start;
    EXPECT_NE(row.find(p < alpha ? "| yes |" : "| no |"), std::string::npos) << row;
    std::cout << "[pmt pair, " << test << "] " << pair["a"].get<std::string>() << " vs " << pair["b"].get<std::string>() << ": ratio "
              << pair["ratio"].get<double>() << ", t = " << t << ", df = " << df << ", p = " << p << (p < alpha ? " (differ)" : " (not told apart)")
              << "\n";
}

TEST_F(PmtPairStudy, DissertationSettingsGrossStudentEveryIterationAValue) {
    const fs::path out = dir / "dissertation";
    const auto r = trn::test::run_trnkit("energy compare " + reports() + " --energy gross --test student --unit frames --no-plots -o " + out.string());
    ASSERT_EQ(r.code, 0) << r.output;
    EXPECT_NE(r.output.find("energy per frame (gross, mJ); tests on frames"), std::string::npos) << r.output;
    check_comparison(out, r.output, {{kNvml.platform, frame_mj(kNvml.platform, "gross_j")}, {kRocm.platform, frame_mj(kRocm.platform, "gross_j")}},
                     "student");
}

TEST_F(PmtPairStudy, OurSettingsNetWelch) {
    const fs::path out = dir / "ours";
    const auto r = trn::test::run_trnkit("energy compare " + reports() + " --no-plots -o " + out.string());
    ASSERT_EQ(r.code, 0) << r.output;
    EXPECT_NE(r.output.find("energy per frame (net, mJ); tests on frames"), std::string::npos) << r.output;
    EXPECT_NE(r.output.find("Mann-Whitney p(Holm) = "), std::string::npos) << r.output;
    check_comparison(out, r.output, {{kNvml.platform, frame_mj(kNvml.platform, "net_j")}, {kRocm.platform, frame_mj(kRocm.platform, "net_j")}}, "welch");
}

}  // namespace
