// The trnkit command line, run as a user would: real processes, real files.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <unistd.h>

#include <opencv2/imgcodecs.hpp>

#include "../common/test_images.hpp"
#include "cli_process.hpp"

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
        {"sobel " + path("map.png") + " --backend cuda", "backend 'cuda' is not built into this trnkit"},
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

TEST_F(Cli, HelpWorksEverywhere) {
    for (const char* sub : {"", "devices", "sobel", "score"}) {
        const Result r = run(std::string(sub) + " --help");
        EXPECT_EQ(r.code, 0) << sub;
        EXPECT_NE(r.output.find("Usage"), std::string::npos) << sub;
    }
}

}  // namespace
