// trn::io::gnuplot_string and the gnuplot runner: every payload stays text, checked both by
// parsing the expression here and by the real gnuplot printing it back.
#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>

#include "payloads.hpp"
#include "security_test_dir.hpp"
#include "trn/error.hpp"
#include "trn/io/gnuplot.hpp"

namespace trn::test {
namespace {
namespace fs = std::filesystem;
using io::gnuplot_sanitized;
using io::gnuplot_string;

// The value of an expression made only of '...' pieces without quotes inside and "\047" / "\100"
// pieces joined by '.'; fails the test on anything else.
std::string evaluate_pieces(const std::string& expr) {
    std::string value;
    std::size_t i = 0;
    while (i < expr.size()) {
        if (expr.compare(i, 6, "\"\\047\"") == 0) {
            value += '\'';
            i += 6;
        } else if (expr.compare(i, 6, "\"\\100\"") == 0) {
            value += '@';
            i += 6;
        } else if (expr[i] == '\'') {
            const std::size_t end = expr.find('\'', i + 1);
            EXPECT_NE(end, std::string::npos) << expr;
            if (end == std::string::npos) return value;
            value += expr.substr(i + 1, end - i - 1);
            i = end + 1;
        } else {
            ADD_FAILURE() << "unexpected character at " << i << " in " << expr;
            return value;
        }
        if (i < expr.size()) {
            EXPECT_EQ(expr[i], '.') << expr;
            ++i;
        }
    }
    return value;
}

TEST(GnuplotString, SanitizedReplacesControlCharactersAndInvalidUtf8) {
    EXPECT_EQ(gnuplot_sanitized("plain text, 1.5 m/km (x_y)"), "plain text, 1.5 m/km (x_y)");
    EXPECT_EQ(gnuplot_sanitized("a\nb\rc\td"), "a?b?c?d");
    EXPECT_EQ(gnuplot_sanitized(std::string("nul") + '\0' + "x\x7f\x1b"), "nul?x??");
    EXPECT_EQ(gnuplot_sanitized("\xc2\x85 C1"), "? C1");
    EXPECT_EQ(gnuplot_sanitized("\xff\xfe"), "??");
    EXPECT_EQ(gnuplot_sanitized("\xc0\xaf overlong"), "?? overlong");
    EXPECT_EQ(gnuplot_sanitized("\xed\xa0\x80 surrogate"), "??? surrogate");
    EXPECT_EQ(gnuplot_sanitized("\xe2\x82"), "??");  // cut sequence
    EXPECT_EQ(gnuplot_sanitized("\xf4\x90\x80\x80"), "????");  // above U+10FFFF
    EXPECT_EQ(gnuplot_sanitized("Jurevi\xc4\x8dius \xe2\x80\x93 \xf0\x9f\x9b\xb8"), "Jurevi\xc4\x8dius \xe2\x80\x93 \xf0\x9f\x9b\xb8");
    EXPECT_EQ(gnuplot_sanitized("quotes ' \" ` \\ ! @ $ ; #"), "quotes ' \" ` \\ ! @ $ ; #");
}

TEST(GnuplotString, ApostrophesAndAtSignsBecomeOctalEscapes) {
    EXPECT_EQ(gnuplot_string(""), "''");
    EXPECT_EQ(gnuplot_string("abc"), "'abc'");
    EXPECT_EQ(gnuplot_string("it's"), R"('it'."\047".'s')");
    EXPECT_EQ(gnuplot_string("''"), R"("\047"."\047")");
    EXPECT_EQ(gnuplot_string("a@b"), R"('a'."\100".'b')");
    EXPECT_EQ(gnuplot_string("a\nb"), "'a?b'");
}

TEST(GnuplotString, EveryPayloadIsOneLineOfQuotedPieces) {
    for (const std::string& p : injection_payloads("/tmp/CANARY")) {
        const std::string expr = gnuplot_string(p);
        for (unsigned char c : expr) EXPECT_TRUE(c >= 0x20 && c != 0x7F && c != '@') << "byte " << int(c) << " in " << expr;
        EXPECT_EQ(evaluate_pieces(expr), gnuplot_sanitized(p)) << expr;
    }
}

class GnuplotRun : public SecurityTest {};

TEST_F(GnuplotRun, RealGnuplotShowsEveryPayloadAsTextAndRunsNothing) {
    if (!io::gnuplot_available()) GTEST_SKIP() << "gnuplot not installed (scripts/install-deps.sh installs gnuplot-nox)";
    const auto payloads = injection_payloads(canary_);
    // gnuplot runs in a private work folder: what it prints goes to a full path (a test's own).
    std::string script = io::gnuplot_png_terminal(400, 300) + "set output 'probe.png'\nset print " + gnuplot_string(path("printed.txt")) + "\n";
    for (const std::string& p : payloads) script += "print " + gnuplot_string(p) + "\n";
    // The same expressions where the plot writers use them: titles, axis labels, tic labels, keys.
    script += "set title " + gnuplot_string(payloads[0]) + "\nset xlabel " + gnuplot_string(payloads[4]) + "\nset ylabel " +
              gnuplot_string(payloads[8]) + "\nset xtics (" + gnuplot_string(payloads[5]) + " 1, " + gnuplot_string(payloads[6]) +
              " 2)\nplot x title " + gnuplot_string(payloads[13]) + ", x*x title " + gnuplot_string(payloads[3]) + "\n";
    io::run_gnuplot({dir_.string(), "probe.gp", script, {}, "probe.log", {io::plot_target(path("probe.png"))}});
    EXPECT_FALSE(fs::exists(canary_)) << "a payload ran a command";
    EXPECT_GT(fs::file_size(path("probe.png")), 1000u);
    std::string expected;
    for (const std::string& p : payloads) expected += gnuplot_sanitized(p) + "\n";
    EXPECT_EQ(slurp(path("printed.txt")), expected);
}

// gnuplot's @macro expander loses track of quotes after a "'" piece and pastes a string variable
// into the line as code; GPVAL_PWD is the folder gnuplot runs in, whose name a user chooses.
TEST_F(GnuplotRun, MacroOfTheOutputFolderNameStaysText) {
    if (!io::gnuplot_available()) GTEST_SKIP() << "gnuplot not installed (scripts/install-deps.sh installs gnuplot-nox)";
    const fs::path folder = dir_ / "x'; system 'touch CANARY'; print '";
    fs::create_directories(folder);
    const std::string label = "it's @GPVAL_PWD";
    // gnuplot runs in a work folder inside `folder`, so GPVAL_PWD still holds the folder's name.
    io::run_gnuplot({folder.string(), "m.gp", "set print " + gnuplot_string((folder / "printed.txt").string()) + "\nprint " + gnuplot_string(label) + "\n", {}, "m.log", {}});
    EXPECT_FALSE(fs::exists(folder / "CANARY")) << "the folder name ran as code";
    EXPECT_EQ(slurp((folder / "printed.txt").string()), label + "\n");
}

TEST(GnuplotNames, OnlyPlainBasenamesAreAccepted) {
    for (const char* ok : {"plot.gp", "a", "fig_3_4_procedural.png", "x-1.0.dat", "_x", ".hidden"}) EXPECT_TRUE(io::is_plain_basename(ok)) << ok;
    for (const char* bad : {"", ".", "..", "-x", "a/b", "a b", "a'b", "a\nb", "a`b`", "@x", "$x", "\xc3\xbc"})
        EXPECT_FALSE(io::is_plain_basename(bad)) << bad;
    EXPECT_EQ(io::plain_basename("my plot\n.png"), "my_plot_.png");
    EXPECT_EQ(io::plain_basename("-rf"), "_rf");
    EXPECT_EQ(io::plain_basename(".."), "_.");
    EXPECT_EQ(io::plain_basename(""), "plot");
    const io::PlotTarget t = io::plot_target("out dir/it's\n.png");
    EXPECT_EQ(t.folder, "out dir");
    EXPECT_EQ(t.name, "it_s_.png");
    EXPECT_EQ(io::plot_target("fig.png").folder, ".");
    EXPECT_THROW(io::plot_target("folder/"), Error);
}

TEST_F(GnuplotRun, RefusesNamesThatAreNotPlainBeforeWritingAnything) {
    const auto image = io::plot_target(path("ok.png"));
    const std::vector<io::GnuplotJob> bad = {
        {dir_.string(), "../x.gp", "", {}, "log", {image}},
        {dir_.string(), "x.gp", "", {{"a\nb.dat", "1\n"}}, "log", {image}},
        {dir_.string(), "x.gp", "", {}, "-log", {image}},
        {dir_.string(), "x.gp", "", {}, "log", {{dir_.string(), "bad name.png", path("bad name.png")}}},
        {dir_.string(), "x.gp", "", {{"x.gp", ""}}, "log", {image}},  // a name used twice
    };
    for (const auto& job : bad) EXPECT_THROW(io::run_gnuplot(job), Error) << job.script_name;
    EXPECT_TRUE(fs::is_empty(dir_));
}

TEST_F(GnuplotRun, ImageIsMovedToTheUserPathThatTheScriptNeverNames) {
    if (!io::gnuplot_available()) GTEST_SKIP() << "gnuplot not installed (scripts/install-deps.sh installs gnuplot-nox)";
    // A file name cannot hold '/': the payload touches CANARY relative to gnuplot's folder (dir_).
    const std::string user = path("my plot\nsystem \"touch CANARY\"\n.png");
    const io::PlotTarget target = io::plot_target(user);
    io::run_gnuplot({target.folder, target.name + ".gp", io::gnuplot_png_terminal(300, 200) + "set output " + gnuplot_string(target.name) +
                     "\nplot x\n", {}, target.name + ".log", {target}});
    EXPECT_GT(fs::file_size(user), 500u);
    EXPECT_FALSE(fs::exists(path(target.name)));
    EXPECT_EQ(slurp(path(target.name + ".gp")).find("system \"touch"), std::string::npos);
    EXPECT_FALSE(fs::exists(canary_));
}

TEST_F(GnuplotRun, FailedScriptIsAnErrorNamingTheLogAndLeavesNoImage) {
    if (!io::gnuplot_available()) GTEST_SKIP() << "gnuplot not installed (scripts/install-deps.sh installs gnuplot-nox)";
    try {
        io::run_gnuplot({dir_.string(), "broken.gp", io::gnuplot_png_terminal(300, 200) + "set output 'broken.png'\nplot nosuchfunction(x)\n",
                         {}, "broken.log", {io::plot_target(path("broken.png"))}});
        ADD_FAILURE() << "no error";
    } catch (const Error& e) {
        EXPECT_NE(std::string(e.what()).find("broken.log"), std::string::npos) << e.what();
    }
    EXPECT_FALSE(fs::exists(path("broken.png")));
    EXPECT_NE(slurp(path("broken.log")).find("nosuchfunction"), std::string::npos);
}

TEST_F(GnuplotRun, MissingGnuplotIsAClearError) {
    // The library reads no PATH: the CLI resolves gnuplot at start-up and sets it ("" = none found).
    const std::string saved = io::gnuplot_program();
    io::set_gnuplot_program(io::find_program("gnuplot", path("empty-bin")));
    EXPECT_FALSE(io::gnuplot_available());
    const std::string folder = path("out\nput");  // the message stays one line
    fs::create_directories(folder);
    try {
        io::run_gnuplot({folder, "x.gp", "plot x\n", {}, "x.log", {io::plot_target(folder + "/x.png")}});
        ADD_FAILURE() << "no error";
    } catch (const Error& e) {
        EXPECT_NE(std::string(e.what()).find("gnuplot not found"), std::string::npos) << e.what();
        EXPECT_EQ(std::string(e.what()).find('\n'), std::string::npos) << e.what();
    }
    io::set_gnuplot_program(saved);
}

}  // namespace
}  // namespace trn::test
