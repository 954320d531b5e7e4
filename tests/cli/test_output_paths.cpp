// Hostile output paths (issue 23, findings 1-4 and the writer side of 8): links, hard links,
// devices, FIFOs, programs and foreign files planted where trnkit writes. Real processes of the
// built trnkit, real files; each test names the finding it covers.
#include <gtest/gtest.h>

#include <fcntl.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <future>
#include <sstream>
#include <thread>

#include <opencv2/imgcodecs.hpp>

#include "../common/test_images.hpp"
#include "../energy/synthetic_run.hpp"
#include "trn/energy/markers.hpp"
#include "trn/energy/parsers.hpp"
#include "temp_folder_test.hpp"
#include "trn/error.hpp"
#include "trn/io/atomic_file.hpp"
#include "trn/io/gnuplot.hpp"
#include "trn/io/output_folder.hpp"

namespace {
namespace fs = std::filesystem;

using Result = trn::test::CliResult;

Result shell(const std::string& line) { return trn::test::run_shell(line); }

const std::string kExe = trn::test::trnkit_exe();  // TRNKIT_UNDER_TEST: another build
Result trnkit(const std::string& args) { return shell(kExe + " " + args + " 2>&1"); }

std::string slurp(const fs::path& p) {
    std::ifstream f(p, std::ios::binary);
    std::ostringstream ss;
    ss << f.rdbuf();
    return ss.str();
}

bool has_gnuplot() { return !trn::io::find_program("gnuplot", "/usr/local/bin:/usr/bin:/bin").empty(); }


class OutputPaths : public trn::test::TempFolderTest {
protected:
    OutputPaths() : TempFolderTest("trnkit_paths_", trnkit) {}
    // A file outside every output folder that a planted link points to.
    std::string victim(const std::string& name) {
        fs::create_directories(path("elsewhere"));
        std::ofstream(path("elsewhere/" + name)) << "precious " << name << "\n";
        return path("elsewhere/" + name);
    }
    // A power log and markers for `energy integrate` (fast, and it plots with --plot).
    std::string integrate_inputs() {
        using namespace trn::energy;
        const test::Timeline tl = test::make_timeline(6, 0.05, 0.05);
        std::ofstream(path("markers.csv")) << format_markers(tl.markers);
        const PowerTrace tr = test::sample_trace(tl.markers, test::TraceClock{}, tl.t0 - 0.2, tl.t0 + 2.5, 1e-3, 1.5, 2.0, 0, true);
        std::ofstream(path("power.log")) << format_trnkit_power(tr);
        return "energy integrate " + path("power.log") + " --markers " + path("markers.csv") + " --json " + path("run.json");
    }
    std::string score_inputs() {
        cv::imwrite(path("map.png"), trn::test::textured_image(240, 200, 1).mat());
        cv::imwrite(path("templ.png"), trn::test::textured_image(240, 200, 1).mat()(cv::Rect(100, 80, 40, 30)));
        std::ofstream poses(path("poses.csv"));
        poses << "x,y,yaw,scale\n";
        for (int i = 0; i < 5; ++i) poses << 60 + i << ",60,0.1,1\n";
        return "score --backend cpu --map " + path("map.png") + " --template " + path("templ.png") + " --poses " + path("poses.csv");
    }
};

// Finding 1: a dataset that ships localize/.trnkit-output and links named like localize's files.
TEST_F(OutputPaths, LinksPlantedInADatasetsLocalizeFolderAreNeverWrittenThrough) {
    simulate("ds", 4);
    fs::create_directories(path("ds/localize"));
    std::ofstream(path("ds/localize/.trnkit-output")) << "trnkit localize\n";
    const std::vector<std::string> names{"summary.json", "localization.csv", "gnuplot.log", "plot_data.tsv", "plot.gp"};
    for (const std::string& n : names) fs::create_symlink(victim(n), path("ds/localize/" + n));
    const Result r = trnkit("localize --dataset " + path("ds") + " --backend cpu" + (has_gnuplot() ? "" : " --no-plots"));
    EXPECT_NE(r.code, 0) << r.output;
    EXPECT_NE(r.output.find("is a symbolic link inside the output folder"), std::string::npos) << r.output;
    for (const std::string& n : names) {
        EXPECT_EQ(slurp(path("elsewhere/" + n)), "precious " + n + "\n") << n << "\n" << r.output;
        EXPECT_TRUE(fs::is_symlink(path("ds/localize/" + n))) << n;
    }
}

// Finding 1: a pre-made default demo folder in the temporary folder with a linked summary.json.
TEST_F(OutputPaths, DemoNeverWritesThroughALinkInItsDefaultFolder) {
    fs::create_directories(path("trnkit-demo"));
    fs::create_symlink(victim("summary.json"), path("trnkit-demo/summary.json"));
    const Result r = shell("TMPDIR=" + dir_.string() + " " + kExe + " demo --backend cpu --distance-km 0.3 --no-plots 2>&1");
    EXPECT_NE(r.code, 0) << r.output;
    EXPECT_EQ(slurp(path("elsewhere/summary.json")), "precious summary.json\n") << r.output;
    // A default folder that is itself a link is refused before any work.
    fs::remove_all(path("trnkit-demo"));
    fs::create_directories(path("elsewhere/demo"));
    fs::create_directory_symlink(path("elsewhere/demo"), path("trnkit-demo"));
    const Result link = shell("TMPDIR=" + dir_.string() + " " + kExe + " demo --backend cpu --distance-km 0.3 --no-plots 2>&1");
    EXPECT_NE(link.code, 0) << link.output;
    EXPECT_NE(link.output.find("is a symbolic link"), std::string::npos) << link.output;
    EXPECT_TRUE(fs::is_empty(path("elsewhere/demo")));
}

// Finding 1: `--out` that is the user's link to a dataset stays a link; the dataset it points to is replaced.
TEST_F(OutputPaths, SimulateIntoALinkedFolderKeepsTheLink) {
    simulate("runs/flight1", 5);
    fs::create_directory_symlink(path("runs/flight1"), path("current"));
    simulate("current", 3);
    EXPECT_TRUE(fs::is_symlink(path("current")));
    EXPECT_EQ(trnkit("simulate --read " + path("runs/flight1")).output.find(": 3 frames") != std::string::npos, true);
}

// Finding 1: a replaced file keeps its permission bits; a hard-linked file is refused, not split.
TEST_F(OutputPaths, ReplacedFilesKeepTheirModeAndHardLinksAreRefused) {
    const std::string score = score_inputs();
    std::ofstream(path("scores.csv")) << "old\n";
    fs::permissions(path("scores.csv"), fs::perms::owner_read | fs::perms::owner_write);
    const Result ok = trnkit(score + " -o " + path("scores.csv"));
    ASSERT_EQ(ok.code, 0) << ok.output;
    EXPECT_NE(slurp(path("scores.csv")), "old\n");
    EXPECT_EQ(fs::status(path("scores.csv")).permissions() & fs::perms::all, fs::perms::owner_read | fs::perms::owner_write);

    std::ofstream(path("linked.csv")) << "linked\n";
    fs::create_hard_link(path("linked.csv"), path("other-name.csv"));
    const Result refused = trnkit(score + " -o " + path("linked.csv"));
    EXPECT_NE(refused.code, 0) << refused.output;
    EXPECT_NE(refused.output.find("hard links"), std::string::npos) << refused.output;
    EXPECT_EQ(slurp(path("linked.csv")), "linked\n");
    EXPECT_EQ(fs::hard_link_count(path("linked.csv")), 2u);
    // The library rule itself, inside and outside an output folder.
    EXPECT_THROW(trn::io::write_file_atomic(path("linked.csv"), "x"), trn::Error);
    fs::create_symlink(path("linked.csv"), path("named-link.csv"));
    std::ofstream(path("plain.csv")) << "plain\n";
    fs::create_symlink(path("plain.csv"), path("link-to-plain.csv"));
    trn::io::write_file_atomic(path("link-to-plain.csv"), "through\n");  // named: followed
    EXPECT_EQ(slurp(path("plain.csv")), "through\n");
    EXPECT_THROW(trn::io::write_file_atomic(path("link-to-plain.csv"), "x", trn::io::Destination::Derived), trn::Error);
    EXPECT_EQ(slurp(path("plain.csv")), "through\n");
}

// Finding 2: a `gnuplot` shipped in the output folder never runs, even with "." and "" in PATH.
TEST_F(OutputPaths, GnuplotIsNeverFoundThroughARelativePathEntry) {
    const std::string cmd = integrate_inputs();
    fs::create_directories(path("out"));
    std::ofstream(path("out/gnuplot")) << "#!/bin/sh\necho ran > " << path("pwned") << "\nexit 0\n";
    fs::permissions(path("out/gnuplot"), fs::perms::owner_all);
    const Result r = shell("cd " + path("out") + " && PATH=.::bin:/usr/local/bin:/usr/bin:/bin " + kExe + " " + cmd + " --plot " +
                           path("out/trace.png") + " 2>&1");
    EXPECT_FALSE(fs::exists(path("pwned"))) << r.output;
    if (has_gnuplot()) EXPECT_EQ(r.code, 0) << r.output;
    EXPECT_EQ(trn::io::find_program("sh", ".::relative/bin"), "");
    EXPECT_EQ(trn::io::find_program("sh", ".:/bin:/usr/bin").front(), '/');
    EXPECT_THROW(trn::io::set_gnuplot_program("gnuplot"), trn::Error);
}

// Finding 3: a FIFO given as --plot is written in place: never unlinked, no sidecars beside it.
TEST_F(OutputPaths, AFifoGivenAsThePlotIsWrittenInPlace) {
    if (!has_gnuplot()) GTEST_SKIP() << "gnuplot not installed";
    const std::string cmd = integrate_inputs();
    ASSERT_EQ(::mkfifo(path("pipe.png").c_str(), 0600), 0);
    auto reader = std::async(std::launch::async, [&] { return slurp(path("pipe.png")); });
    const Result r = trnkit(cmd + " --plot " + path("pipe.png"));
    EXPECT_EQ(r.code, 0) << r.output;
    if (r.code != 0) {  // unblock the reader
        const int fd = ::open(path("pipe.png").c_str(), O_WRONLY | O_NONBLOCK);
        if (fd >= 0) ::close(fd);
    }
    const std::string png = reader.get();
    EXPECT_EQ(png.substr(1, 3), "PNG");
    struct stat st {};
    ASSERT_EQ(::lstat(path("pipe.png").c_str(), &st), 0);
    EXPECT_TRUE(S_ISFIFO(st.st_mode));
    for (const char* side : {"pipe.png.gp", "pipe.png.log", "pipe.gp", "pipe.log"}) EXPECT_FALSE(fs::exists(path(side))) << side;
    for (const auto& e : fs::directory_iterator(dir_))
        EXPECT_EQ(e.path().filename().string().find(".gp"), std::string::npos) << e.path();
}

// Finding 4: only marked staging folders of dead processes are swept; a user's look-alike stays.
TEST_F(OutputPaths, SimulateSweepsOnlyItsOwnMarkedStagingFolders) {
    const pid_t dead = ::fork();
    if (dead == 0) ::_exit(0);
    ::waitpid(dead, nullptr, 0);
    const std::string users = path("results.partial-" + std::to_string(dead));
    fs::create_directories(users);
    std::ofstream(users + "/thesis.tex") << "years of work\n";
    simulate("results", 2);
    EXPECT_EQ(slurp(users + "/thesis.tex"), "years of work\n");
}

// Finding 4: a rerun of simulate over its own dataset keeps what it did not write.
TEST_F(OutputPaths, SimulateRerunKeepsFilesItDidNotWrite) {
    simulate("ds", 5);
    const Result loc = trnkit("localize --dataset " + path("ds") + " --backend cpu --no-plots");
    ASSERT_EQ(loc.code, 0) << loc.output;
    std::ofstream(path("ds/NOTES.txt")) << "my notes\n";
    simulate("ds", 3);
    EXPECT_EQ(slurp(path("ds/NOTES.txt")), "my notes\n");
    EXPECT_TRUE(fs::exists(path("ds/localize/summary.json")));
    EXPECT_NE(trnkit("simulate --read " + path("ds")).output.find(": 3 frames"), std::string::npos);
    // The marker lists what simulate wrote, and only that.
    const std::string marker = slurp(path("ds/.trnkit-output"));
    EXPECT_NE(marker.find("\nmetadata.csv\n"), std::string::npos) << marker;
    EXPECT_EQ(marker.find("NOTES.txt"), std::string::npos) << marker;
}

// Finding 4: register --air-out is an output folder like any other.
TEST_F(OutputPaths, RegisterRefusesAForeignAirFolder) {
    cv::imwrite(path("map.png"), trn::test::textured_image(240, 200, 1).mat());
    cv::imwrite(path("f0.png"), trn::test::textured_image(240, 200, 1).mat()(cv::Rect(100, 80, 40, 30)));
    fs::create_directories(path("theirs"));
    std::ofstream(path("theirs/metadata.csv")) << "someone else's\n";
    const Result r = trnkit("register --map " + path("map.png") + " " + path("f0.png") + " --air-out " + path("theirs"));
    EXPECT_NE(r.code, 0) << r.output;
    EXPECT_NE(r.output.find("--air-out " + path("theirs") + ": not empty"), std::string::npos) << r.output;
    EXPECT_EQ(slurp(path("theirs/metadata.csv")), "someone else's\n");
}

// Finding 4: `--plot "my report.png"` is drawn under "my_report.png" in a work folder: a file of
// that name is not touched; sidecars never replace someone else's file.
TEST_F(OutputPaths, PlotNamesNeverTakeAnotherFile) {
    const std::string cmd = integrate_inputs();
    std::ofstream(path("my_report.png")) << "mine\n";
    std::ofstream(path("trace.png.gp")) << "my own gnuplot script\n";  // the script's name: the image's + ".gp"
    const Result sidecar = trnkit(cmd + " --plot " + path("trace.png"));
    EXPECT_NE(sidecar.code, 0) << sidecar.output;
    EXPECT_NE(sidecar.output.find("trace.png.gp: exists and is not a file of an earlier trnkit plot"), std::string::npos) << sidecar.output;
    EXPECT_EQ(slurp(path("trace.png.gp")), "my own gnuplot script\n");
    EXPECT_FALSE(fs::exists(path("trace.png")));
    if (!has_gnuplot()) GTEST_SKIP() << "gnuplot not installed";
    const Result r = trnkit(cmd + " --plot '" + path("my report.png") + "'");
    ASSERT_EQ(r.code, 0) << r.output;
    EXPECT_EQ(slurp(path("my_report.png")), "mine\n");
    EXPECT_EQ(slurp(path("my report.png")).substr(1, 3), "PNG");
    // Its own sidecars from the first run are replaced by the second.
    const Result again = trnkit(cmd + " --plot '" + path("my report.png") + "'");
    EXPECT_EQ(again.code, 0) << again.output;
    for (const auto& e : fs::directory_iterator(dir_))
        EXPECT_EQ(e.path().filename().string().find(".trnkit-plot"), std::string::npos) << e.path();
}

// Finding 4: the output is never one of the inputs.
TEST_F(OutputPaths, ScoreRefusesToWriteOverItsOwnInput) {
    const std::string score = score_inputs();
    const std::string poses = slurp(path("poses.csv"));
    const Result r = trnkit(score + " -o " + path("poses.csv"));
    EXPECT_NE(r.code, 0) << r.output;
    EXPECT_NE(r.output.find("is the same file as --poses"), std::string::npos) << r.output;
    EXPECT_EQ(slurp(path("poses.csv")), poses);
    fs::create_symlink(path("poses.csv"), path("alias.csv"));
    EXPECT_NE(trnkit(score + " -o " + path("alias.csv")).code, 0);
    EXPECT_EQ(slurp(path("poses.csv")), poses);
}

// Finding 4: a localize rerun that fails at the plots leaves no plot of the earlier run beside its
// new summary; files the command did not write stay.
TEST_F(OutputPaths, FailedLocalizeRerunLeavesNoOldPlots) {
    if (!has_gnuplot()) GTEST_SKIP() << "gnuplot not installed";
    simulate("ds", 4);
    const std::string cmd = "localize --dataset " + path("ds") + " --backend cpu --out " + path("res");
    const Result first = trnkit(cmd);
    ASSERT_EQ(first.code, 0) << first.output;
    ASSERT_TRUE(fs::exists(path("res/trajectory.png")));
    std::ofstream(path("res/notes.txt")) << "mine\n";
    const Result failed = shell("PATH=/nonexistent " + kExe + " " + cmd + " 2>&1");
    EXPECT_NE(failed.code, 0) << failed.output;
    EXPECT_NE(failed.output.find("gnuplot not found"), std::string::npos) << failed.output;
    EXPECT_TRUE(fs::exists(path("res/summary.json")));
    EXPECT_FALSE(fs::exists(path("res/trajectory.png")));
    EXPECT_FALSE(fs::exists(path("res/error.png")));
    EXPECT_EQ(slurp(path("res/notes.txt")), "mine\n");
}

// Finding 8 (writer side): runs into one folder at once never delete each other's plots.
TEST_F(OutputPaths, LocalizeRunsIntoOneFolderAtOnceLeaveCompletePlots) {
    if (!has_gnuplot()) GTEST_SKIP() << "gnuplot not installed";
    simulate("ds", 4);
    const std::string cmd = kExe + " localize --dataset " + path("ds") + " --backend cpu --out " + path("res") + " 2>&1";
    const Result r = shell("(" + cmd + ") > " + path("a.txt") + " & (" + cmd + ") > " + path("b.txt") + " & (" + cmd + ") > " +
                           path("c.txt") + " & wait");
    for (const char* log : {"a.txt", "b.txt", "c.txt"}) EXPECT_EQ(slurp(path(log)).find("trnkit: error"), std::string::npos) << slurp(path(log));
    EXPECT_GT(fs::file_size(path("res/trajectory.png")), 1000u);
    EXPECT_GT(fs::file_size(path("res/error.png")), 1000u);
    EXPECT_TRUE(fs::exists(path("res/summary.json")));
    for (const auto& e : fs::directory_iterator(path("res")))
        EXPECT_EQ(e.path().filename().string().find(".tmp-"), std::string::npos) << e.path();
}

}  // namespace
