// The trnkit command line, run as a user would: real processes, real files.
#include <gtest/gtest.h>

#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <fstream>

#include <opencv2/imgcodecs.hpp>

#include "../common/peak_rss.hpp"
#include "../common/test_images.hpp"
#include "cli_process.hpp"
#include "trn/build_info.hpp"

namespace {

using Result = trn::test::CliResult;
Result run(const std::string& args) { return trn::test::run_trnkit(args); }

class Cli : public testing::Test {
protected:
    void SetUp() override {
        dir_ = std::filesystem::temp_directory_path() / ("trnkit_cli_" + std::to_string(::getpid()));
        std::filesystem::create_directories(dir_);
        cv::imwrite(path("map.png"), trn::test::textured_image(240, 200, 1).mat());
        cv::imwrite(path("templ.png"), trn::test::textured_image(240, 200, 1).mat()(cv::Rect(100, 80, 40, 30)));
        std::ofstream(path("poses.csv")) << "x,y,yaw,scale\n119.5,94.5,0,1\n60,60,0.5,1\n";
    }
    void TearDown() override { std::filesystem::remove_all(dir_); }
    std::string path(const std::string& name) const { return (dir_ / name).string(); }
    std::filesystem::path dir_;
};

TEST_F(Cli, DevicesListsCpuBackendsAndExplainsMissingOnes) {
    const Result r = run("devices --verbose");
    EXPECT_EQ(r.code, 0) << r.output;
    EXPECT_NE(r.output.find("  cpu-ref  [cpu]"), std::string::npos) << r.output;
    EXPECT_NE(r.output.find("  cpu  [cpu]"), std::string::npos) << r.output;
    for (const char* family : {"opencl - ", "vulkan - "}) EXPECT_NE(r.output.find(family), std::string::npos) << r.output;
}

// The library reads no environment; the CLI turns the documented TRN_* variables into
// BackendOptions (apps/trnkit/backend_env.cpp): a good value reaches the backend, a malformed one
// is one line naming the variable (it was silently ignored before).
TEST_F(Cli, BackendVariablesReachTheBackendThroughTheCli) {
    ::setenv("TRN_CPU_THREADS", "3", 1);
    Result r = run("devices --verbose");
    EXPECT_EQ(r.code, 0) << r.output;
    EXPECT_NE(r.output.find("3 threads"), std::string::npos) << r.output;
    ::setenv("TRN_CPU_THREADS", "abc", 1);
    r = run("score --map " + path("map.png") + " --template " + path("templ.png") + " --poses " + path("poses.csv") + " --backend cpu");
    ::unsetenv("TRN_CPU_THREADS");
    EXPECT_EQ(r.code, 1) << r.output;
    EXPECT_NE(r.output.find("TRN_CPU_THREADS='abc'"), std::string::npos) << r.output;
    EXPECT_EQ(std::count(r.output.begin(), r.output.end(), '\n'), 1) << r.output;
}

// `trnkit --version`: the version and the git commit trn::build_info() was built with.
TEST_F(Cli, VersionPrintsVersionAndCommit) {
    const Result r = run("--version");
    EXPECT_EQ(r.code, 0) << r.output;
    EXPECT_NE(r.output.find("trnkit " + std::string(trn::build_info().version)), std::string::npos) << r.output;
    EXPECT_NE(r.output.find(std::string(trn::build_info().git_commit)), std::string::npos) << r.output;
}

TEST_F(Cli, ScoreWritesCsvWithTheTruePoseBest) {
    const Result r = run("score --map " + path("map.png") + " --template " + path("templ.png") + " --poses " + path("poses.csv") +
                         " --backend cpu --out " + path("scores.csv"));
    ASSERT_EQ(r.code, 0) << r.output;
    std::ifstream f(path("scores.csv"));
    std::string header, first, second;
    std::getline(f, header);
    std::getline(f, first);
    std::getline(f, second);
    EXPECT_EQ(header, "index,x,y,yaw,scale,ncc,cc,ssd,valid_samples,flags");
    EXPECT_NE(first.find(",1.0000000,"), std::string::npos) << first;  // ncc of the exact crop
    EXPECT_NE(second.rfind(",1200,0"), std::string::npos) << second;
}

TEST_F(Cli, SobelWritesBothGradients) {
    const Result r = run("sobel " + path("map.png") + " --backend cpu-ref --out " + path("sob"));
    ASSERT_EQ(r.code, 0) << r.output;
    EXPECT_FALSE(cv::imread(path("sob/gx.png")).empty());
    EXPECT_FALSE(cv::imread(path("sob/gy.png")).empty());
}

TEST_F(Cli, BadInputGivesOneClearLineAndNonZeroExit) {
    std::ofstream(path("corrupt.png")) << "\x89PNG\r\n\x1a\nthis is not a png";
    std::ofstream(path("bad.csv")) << "x,y,yaw,scale\n1,2,nan,1\n";
    const struct {
        std::string args, expect;
    } cases[] = {
        {"sobel " + path("nothere.png"), "nothere.png: no such file"},
        {"sobel " + path("corrupt.png"), "corrupt.png: not a readable image"},
        {"sobel " + path("map.png") + " --backend metal", "backend 'metal' is not built into this trnkit"},
        {"score --map " + path("templ.png") + " --template " + path("map.png") + " --poses " + path("poses.csv"),
         "smaller than the template"},
        {"score --map " + path("map.png") + " --template " + path("templ.png") + " --poses " + path("bad.csv"),
         "bad.csv:2: field 3 is not finite"},
        {"score --map " + path("map.png") + " --template " + path("templ.png") + " --poses " + path("poses.csv") +
             " --sampling random:x",
         "--sampling 'random:x'"},
        {"score --map " + path("map.png"), "--template is required"},
    };
    for (const auto& c : cases) {
        const Result r = run(c.args);
        EXPECT_NE(r.code, 0) << c.args;
        EXPECT_NE(r.output.find(c.expect), std::string::npos) << c.args << "\n" << r.output;
    }
}

// One error, one line: a newline inside a file name or an option value is shown escaped, and
// CLI11's parse errors carry no second "Run with --help" line (FUZZ-FINDINGS #4, #16).
TEST_F(Cli, ErrorsStayOnOneLineWhateverTheyQuote) {
    const struct {
        std::string args, expect;
    } cases[] = {
        {"sobel '" + path("no\nthere.png") + "'", "no\\nthere.png: no such file"},
        {"energy inspect '--opt=line1\nline2\n' " + path("poses.csv"), "line1\\nline2\\n"},
        {"score --map " + path("map.png"), "--template is required"},
        {"sobel --bogus-option " + path("map.png"), "--bogus-option"},
    };
    for (const auto& c : cases) {
        const Result r = run(c.args);
        EXPECT_NE(r.code, 0) << c.args;
        EXPECT_EQ(std::count(r.output.begin(), r.output.end(), '\n'), 1) << c.args << "\n" << r.output;
        EXPECT_EQ(r.output.rfind("trnkit: error: ", 0), 0u) << r.output;
        EXPECT_NE(r.output.find(c.expect), std::string::npos) << c.args << "\n" << r.output;
    }
}

TEST_F(Cli, HelpWorksEverywhere) {
    for (const char* sub : {"", "devices", "sobel", "score"}) {
        const Result r = run(std::string(sub) + " --help");
        EXPECT_EQ(r.code, 0) << sub;
        EXPECT_NE(r.output.find("Usage"), std::string::npos) << sub;
    }
}

// Largest RSS of any child process so far, in bytes.
double largest_child_rss() {
    rusage children{};
    EXPECT_EQ(getrusage(RUSAGE_CHILDREN, &children), 0);
    return double(children.ru_maxrss) * 1024;  // ru_maxrss is in KiB
}

// Too-large inputs are refused up front (header / option sizes), in one line, before any big
// allocation (each case would need 180 MB to 4.9 GB): no child grows more than 64 MiB past what a
// child that does nothing (`trnkit --version`) takes in the same build, and in the Release build
// none grows past 150 MiB at all (they take ~57 MB, --version's share). A sanitized build has its
// own bound: ASan's runtime, shadow and allocator make even --version take ~2.5x as much, so there
// the absolute bound does not apply and the 64 MiB allowance carries ASan's 1/8 shadow on top.
TEST_F(Cli, OversizedInputsFailAtOnceWithTheLimit) {
    ASSERT_EQ(run("--version").code, 0);
    const double idle = largest_child_rss();  // the first child (ctest runs each test in its own process)
    const double allowance = 64.0 * (1 << 20) * (trn::test::kUnderAddressSanitizer ? trn::test::kAddressSanitizerRssSlack : 1.0);
    std::printf("trnkit --version: %.1f MB peak RSS%s\n", idle / 1e6, trn::test::kUnderAddressSanitizer ? " (ASan)" : "");
    // A PNG header claiming 40000x40000 pixels and no pixel data: refused before decoding.
    unsigned char png[33] = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1A, '\n', 0, 0, 0, 13, 'I', 'H', 'D', 'R',
                             0, 0, 0x9C, 0x40, 0, 0, 0x9C, 0x40, 8};
    std::ofstream(path("huge.png"), std::ios::binary).write(reinterpret_cast<const char*>(png), sizeof png);
    const struct {
        std::string args, expect;
    } cases[] = {
        {"score --map " + path("huge.png") + " --template " + path("templ.png") + " --poses " + path("poses.csv"),
         "huge.png: image 40000x40000 needs ~3.2 GB (limit 1073741824 pixels, e.g. 32768x32768)"},
        {"sobel " + path("huge.png"), "huge.png: image 40000x40000 needs ~3.2 GB"},
        {"simulate --scenario FC-300 --size-m 20000 --mpp 0.25 --frames 2 --out " + path("flight"), "image 80000x80000 is too large: its sides may be at most 65536 pixels"},
    };
    for (const auto& c : cases) {
        const Result r = run(c.args);
        EXPECT_NE(r.code, 0) << c.args;
        EXPECT_NE(r.output.find(c.expect), std::string::npos) << c.args << "\n" << r.output;
        EXPECT_EQ(std::count(r.output.begin(), r.output.end(), '\n'), 1) << r.output;
        const double largest = largest_child_rss();
        EXPECT_LT(largest, idle + allowance) << c.args << ": largest child so far " << largest / 1e6 << " MB, --version "
                                             << idle / 1e6 << " MB";
        if (!trn::test::kUnderAddressSanitizer) {
            EXPECT_LT(largest, 150.0 * (1 << 20)) << c.args << ": largest child so far " << largest / 1e6 << " MB";
        }
    }
    std::printf("largest child: %.1f MB peak RSS\n", largest_child_rss() / 1e6);    // Particle counts beyond trn::limits::kMaxParticles stop at the option parser (CLI11's two-line
    // message), before the backend is even created.
    const Result r = run("frames --kernel ncc --particles 5000000 --frames 1 --out " + path("m.csv"));
    EXPECT_NE(r.code, 0);
    EXPECT_NE(r.output.find("--particles: '5000000' is outside [1, 4194304]"), std::string::npos) << r.output;
    EXPECT_FALSE(std::filesystem::exists(path("m.csv")));
}

}  // namespace
