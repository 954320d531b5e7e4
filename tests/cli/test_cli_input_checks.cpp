// Nonsense in numbers, AIR folders and maps stops trnkit with a message naming the option or the
// file and line, instead of wrapping, silently falling back, or printing NaN with exit 0.
// Each case also carries something that makes the old, unchecked code fail fast (an unknown
// scenario or backend), so a missing check shows up as a wrong message, never as a long run.
#include <gtest/gtest.h>

#include <unistd.h>

#include <filesystem>
#include <fstream>

#include <opencv2/imgcodecs.hpp>

#include "../common/test_images.hpp"
#include "cli_process.hpp"

namespace {

using trn::test::run_trnkit;

class CliInput : public testing::Test {
protected:
    void SetUp() override {
        dir_ = std::filesystem::temp_directory_path() / ("trnkit_cli_input_" + std::to_string(::getpid()));
        std::filesystem::remove_all(dir_);
        std::filesystem::create_directories(dir_);
    }
    void TearDown() override { std::filesystem::remove_all(dir_); }
    std::string path(const std::string& name) const { return (dir_ / name).string(); }

    // Runs each case; every one must exit non-zero with `expect` in its output.
    void expect_refused(const std::vector<std::pair<std::string, std::string>>& cases) {
        for (const auto& [args, expect] : cases) {
            const auto r = run_trnkit(args);
            EXPECT_NE(r.code, 0) << args << "\n" << r.output;
            EXPECT_NE(r.output.find(expect), std::string::npos) << args << "\nexpected: " << expect << "\ngot: " << r.output;
        }
    }

    // A tiny AIR flight: a 240x200 map, a 64x48 camera at 5 fps, one frame per row.
    std::string flight(const std::string& name, const std::vector<std::string>& rows, int frame_w = 64, int frame_h = 48,
                       const std::string& info = "") {
        const std::string d = path(name);
        std::filesystem::create_directories(d);
        cv::imwrite(d + "/map.png", trn::test::textured_image(240, 200, 1).mat());
        std::ofstream(d + "/flight.json") << (info.empty() ? R"({"scenario": "T", "map_file": "map.png", "metres_per_pixel": 1,
            "camera": {"width": 64, "height": 48, "hfov_deg": 60}, "fps": 5})"
                                                           : info);
        std::ofstream csv(d + "/metadata.csv");
        csv << "Filename,Latitude,Longitude,RelativeAltitude,ImuX,ImuY,ImuZ,ImuW,PoseX,PoseY,PoseZ,OrientationX,OrientationY,"
               "OrientationZ,OrientationW,MapX,MapY,SvoX,SvoY,SvoZ\n";
        for (const std::string& r : rows) {
            csv << r << "\n";
            const std::string file = r.substr(0, r.find(','));
            if (file.rfind("gone", 0) != 0) cv::imwrite(d + "/" + file, trn::test::textured_image(frame_w, frame_h, 3).mat());
        }
        return d;
    }
    static std::string row(const std::string& file, const std::string& altitude = "200", const std::string& map_x = "120",
                           const std::string& svo_x = "0") {
        return file + ",47.1,8.2," + altitude + ",0,0,0.7071068,0.7071068,0,0,200,0,0,0.7071068,0.7071068," + map_x + ",100," +
               svo_x + ",0,200";
    }
    std::string localize(const std::string& folder) const {
        return "localize --dataset " + folder + " --backend cpu --template-width 32 --max-particles 100 --min-particles 50 --no-plots --out " +
               folder + "/out";
    }

    std::filesystem::path dir_;
};

TEST_F(CliInput, CountsRefuseSignsOverflowAndOutOfRangeNamingTheOption) {
    cv::imwrite(path("map.png"), trn::test::textured_image(20, 20, 1).mat());
    expect_refused({
        {"simulate --scenario NOPE --frames -1 --out " + path("f"), "--frames: '-1' is not a whole number in [1, 200000]"},
        {"simulate --scenario NOPE --frames 99999999999999999999 --out " + path("f"), "--frames: '99999999999999999999'"},
        {"simulate --scenario NOPE --seed -1 --out " + path("f"), "--seed: '-1' is not a whole number"},
        {"simulate --scenario NOPE --base-year 20008 --out " + path("f"), "--base-year: '20008' is outside [1900, 2200]"},
        {"energy integrate " + path("none.log") + " --markers " + path("none.csv") + " --min-samples -1", "--min-samples: '-1'"},
        {"localize --dataset " + path("none") + " --max-particles -1", "--max-particles: '-1'"},
        {"localize --dataset " + path("none") + " --particles 0", "--particles: '0' is outside [1, 4194304]"},
        {"frames --backend nosuch --frames 0", "--frames: '0' is outside"},
        {"frames --backend nosuch --particles -5", "--particles: '-5'"},
        {"frames --backend nosuch --size 4k", "--size: 4k not in {480p,720p,1080p}"},
        {"check -n 0x10", "--particles: '0x10' is not a whole number"},
        {"experiment metrics --backend nosuch --out " + path("e") + " --shard 1/99999999999999999999",
         "--shard '1/99999999999999999999' must be i/n"},
        {"experiment metrics --backend nosuch --out " + path("e") + " --shard 0/2", "--shard '0/2' must be i/n"},
        {"sobel " + path("map.png") + " --backend cpu:99999999999999999999", "device index 99999999999999999999 out of range"},
    });
    EXPECT_FALSE(std::filesystem::exists(path("f"))) << "a refused simulate must not create its output folder";
}

TEST_F(CliInput, RealsRefuseNanInfAndOutOfRangeNamingTheOption) {
    expect_refused({
        {"simulate --scenario NOPE --seconds 0 --out " + path("f"), "--seconds: '0' is outside (0, 4000]"},
        {"simulate --scenario NOPE --seconds nan --out " + path("f"), "--seconds: 'nan' is not a finite number"},
        {"simulate --scenario NOPE --seconds -3 --out " + path("f"), "--seconds: '-3' is outside"},
        {"simulate --scenario NOPE --mpp -1 --out " + path("f"), "--mpp: '-1' is outside (0, 1000]"},
        {"simulate --scenario NOPE --mpp nan --out " + path("f"), "--mpp: 'nan' is not a finite number"},
        {"simulate --scenario NOPE --fov 170 --out " + path("f"), "--fov: '170' is outside (1, 170)"},
        {"simulate --scenario NOPE --lat 91 --lon 8 --out " + path("f"), "--lat: '91' is outside [-90, 90]"},
        {"frames --backend nosuch --idle-ms nan", "--idle-ms: 'nan' is not a finite number"},
        {"frames --backend nosuch --idle-ms inf", "--idle-ms: 'inf' is not a finite number"},
        {"frames --backend nosuch --lead-idle-ms -1", "--lead-idle-ms: '-1' is outside [0, 600000]"},
        {"demo --scenario NOPE --rate 0", "--rate: '0' is outside (0, 1000]"},
        {"demo --scenario NOPE --distance-km inf", "--distance-km: 'inf' is not a finite number"},
        {"demo --scenario NOPE --sparse nan", "--sparse: 'nan' is not a finite number"},
        {"localize --dataset " + path("none") + " --rate -5", "--rate: '-5' is outside"},
        {"localize --dataset " + path("none") + " --mpp nan", "--mpp: 'nan' is not a finite number"},
        {"energy sample --period-ms 0 --source nosuch", "--period-ms: '0' is outside (0, 60000]"},
        {"energy integrate " + path("none.log") + " --markers " + path("none.csv") + " --offset nan", "--offset: 'nan'"},
        {"score --map m --template t --poses p --min-valid 2", "--min-valid: '2' is outside [0, 1]"},
        {"energy integrate-span " + path("none.log") + " --start 5 --end 1", "--end 1.000000 must be after --start 5.000000"},
        {"score --map m --template t --poses p --sampling random:nan", "--sampling 'random:nan'"},
        {"score --map m --template t --poses p --sampling random:0.5:-1", "--sampling 'random:0.5:-1'"},
    });
}

TEST_F(CliInput, ScoreNamesItsFilesWhenTheLibraryRefuses) {
    cv::imwrite(path("small.png"), trn::test::textured_image(20, 20, 1).mat());
    cv::imwrite(path("templ.png"), trn::test::textured_image(40, 30, 2).mat());
    std::ofstream(path("poses.csv")) << "x,y,yaw,scale\n10,10,0,1\n";
    std::ofstream(path("empty.csv")) << "x,y,yaw,scale\n";
    expect_refused({
        {"score --backend cpu --map " + path("small.png") + " --template " + path("templ.png") + " --poses " + path("poses.csv"),
         "--poses " + path("poses.csv") + ": score: map 20x20 is smaller than the template 40x30"},
        {"score --backend cpu --map " + path("templ.png") + " --template " + path("small.png") + " --poses " + path("empty.csv"),
         "empty.csv: no poses to score"},
    });
}

TEST_F(CliInput, LocalizeRefusesBrokenAirFoldersNamingFileAndLine) {
    const std::string ok = row("frame_000000.png");
    const std::string big_camera = R"({"metres_per_pixel": 1, "map_file": "map.png", "camera": {"width": 100000, "height": 48, "hfov_deg": 60}})";
    const std::string no_fps = R"({"metres_per_pixel": 1, "map_file": "map.png", "camera": {"width": 64, "height": 48, "hfov_deg": 60}, "fps": 0})";
    const std::string wide_fov = R"({"metres_per_pixel": 1, "map_file": "map.png", "camera": {"width": 64, "height": 48, "hfov_deg": 600}})";
    expect_refused({
        {"localize --backend cpu --no-plots --min-particles 200 --max-particles 100 --dataset " + flight("min_max", {ok}),
         "--min-particles 200 exceeds --max-particles 100"},
        {localize(flight("header_only", {})), "header_only/metadata.csv: no frame rows after the header"},
        {localize(flight("huge_x", {row("frame_000000.png", "200", "1e300")})), "huge_x/metadata.csv:2: MapX 1e+300 is outside"},
        {localize(flight("no_altitude", {row("frame_000000.png", "0")})),
         "no_altitude/metadata.csv:2: RelativeAltitude 0 m is not a flight altitude"},  // the reader's one check (issue 23)
        {localize(flight("off_map", {row("frame_000000.png", "200", "500")})),
         "off_map/metadata.csv:2 (frame_000000.png): the true position MapX,MapY 500,100 is outside the 240x200 px map"},
        {localize(flight("all_missing", {row("gone_000000.png"), row("gone_000001.png")})),
         "none of the 2 frames the filter would use exists (first: " + path("all_missing") + "/metadata.csv:2 (gone_000000.png))"},
        {localize(flight("duplicated", {ok, ok})), "duplicated/metadata.csv:3: frame_000000.png is listed again (first on line 2)"},
        {localize(flight("shuffled", {row("frame_000002.png"), ok})),
         "shuffled/metadata.csv:3: frame_000000.png comes after frame_000002.png"},
        {localize(flight("big_camera", {ok}, 64, 48, big_camera)), "big_camera/flight.json: camera.width 100000 must be a whole number"},
        {localize(flight("no_fps", {ok}, 64, 48, no_fps)), "no_fps/flight.json: fps 0 must be a number in (0, 1000]"},
        {localize(flight("wide_fov", {ok}, 64, 48, wide_fov)), "wide_fov/flight.json: camera.hfov_deg 600 must be a number"},
    });
}

// A frame of another size than flight.json's camera, the same view resized, is scored at the scale
// of its own width (issue 12 item 4), and a folder without flight.json runs from --map/--mpp/--hfov-deg.
TEST_F(CliInput, LocalizeTakesFramesOfAnySizeAndFoldersWithoutFlightJson) {
    const std::string small = flight("small_frame", {row("frame_000000.png"), row("frame_000001.png")}, 32, 24);
    const auto r = run_trnkit(localize(small));
    EXPECT_EQ(r.code, 0) << r.output;
    const std::string bare = flight("bare", {row("frame_000000.png"), row("frame_000001.png")});
    std::filesystem::remove(bare + "/flight.json");
    const auto refused = run_trnkit(localize(bare));
    EXPECT_EQ(refused.code, 1) << refused.output;
    EXPECT_NE(refused.output.find("--map: required: " + bare + "/flight.json is absent"), std::string::npos) << refused.output;
    const auto ran = run_trnkit(localize(bare) + " --map " + bare + "/map.png --mpp 1 --hfov-deg 60");
    EXPECT_EQ(ran.code, 0) << ran.output;
}

// A frame that is not the camera's view at another resolution (another aspect ratio: a crop, a
// rotated frame, another camera) is refused before the run, naming the file and both sizes, and
// nothing is written (issue 45 class 6: localize never compared a frame's size with the folder's
// camera and scored such a frame at a focal length its width does not give).
TEST_F(CliInput, LocalizeRefusesAFrameOfAnotherAspectRatioBeforeWritingAnything) {
    const std::string d = flight("cropped", {row("frame_000000.png"), row("frame_000001.png")});
    cv::imwrite(d + "/frame_000001.png", trn::test::textured_image(64, 20, 3).mat());
    const auto r = run_trnkit(localize(d));
    EXPECT_EQ(r.code, 1) << r.output;
    EXPECT_NE(r.output.find(d + "/metadata.csv:3 (frame_000001.png): the frame " + d + "/frame_000001.png is 64x20 px, but the folder's camera "
                                "(flight.json) is 64x48 px: another aspect ratio"),
              std::string::npos)
        << r.output;
    EXPECT_FALSE(std::filesystem::exists(d + "/out")) << "validate first: no output before the refusal";

    const std::string square = flight("square", {row("frame_000000.png")}, 48, 48);  // even the first frame is checked
    const auto s = run_trnkit(localize(square));
    EXPECT_EQ(s.code, 1) << s.output;
    EXPECT_NE(s.output.find(square + "/metadata.csv:2 (frame_000000.png): the frame " + square + "/frame_000000.png is 48x48 px, but the "
                                     "folder's camera (flight.json) is 64x48 px"),
              std::string::npos)
        << s.output;

    // Without flight.json the first frame is the reference.
    const std::string bare = flight("bare_mixed", {row("frame_000000.png"), row("frame_000001.png")});
    std::filesystem::remove(bare + "/flight.json");
    cv::imwrite(bare + "/frame_000001.png", trn::test::textured_image(36, 48, 3).mat());
    const auto b = run_trnkit(localize(bare) + " --map " + bare + "/map.png --mpp 1 --hfov-deg 60");
    EXPECT_EQ(b.code, 1) << b.output;
    EXPECT_NE(b.output.find(bare + "/metadata.csv:3 (frame_000001.png): the frame " + bare + "/frame_000001.png is 36x48 px, but the first frame (" +
                            bare + "/frame_000000.png) is 64x48 px"),
              std::string::npos)
        << b.output;
    EXPECT_FALSE(std::filesystem::exists(bare + "/out"));
}

TEST_F(CliInput, LocalizeNamesTheRowWhenTheLibraryRefuses) {
    const std::string vga = R"({"metres_per_pixel": 1, "map_file": "map.png", "camera": {"width": 640, "height": 480, "hfov_deg": 60}, "fps": 5})";
    const std::string d = flight("vga", {row("frame_000000.png")}, 640, 480, vga);
    expect_refused({{"localize --backend cpu --no-plots --template-width 300 --dataset " + d,
                     d + "/metadata.csv:2 (frame_000000.png): score: map 240x200 is smaller than the template 300x225"}});
}

TEST_F(CliInput, LocalizeWarnsAboutAFewMissingFramesAndOdometryOffTheMapAndRuns) {
    const std::string d =
        flight("some_missing", {row("frame_000000.png"), row("gone_000001.png"), row("frame_000002.png", "200", "120", "500")});
    const auto r = run_trnkit(localize(d));
    EXPECT_EQ(r.code, 0) << r.output;
    EXPECT_NE(r.output.find("warning: " + d + ": 1 of 3 frames are missing and will be skipped (first: " + d +
                            "/metadata.csv:3 (gone_000001.png))"),
              std::string::npos)
        << r.output;
    EXPECT_NE(r.output.find("warning: " + d + ": the odometry leaves the map on 1 of 3 rows (first: " + d +
                            "/metadata.csv:4 (frame_000002.png))"),
              std::string::npos)
        << r.output;
}

TEST_F(CliInput, CheckFailsWhenEveryParticleIsFlagged) {
    cv::imwrite(path("flat.png"), cv::Mat(250, 300, CV_8UC1, cv::Scalar(128)));
    const auto r = run_trnkit("check -n 10 --map " + path("flat.png"));
    EXPECT_NE(r.code, 0) << r.output;
    EXPECT_NE(r.output.find("cpu-ref: the true pose is flagged (flat map patch, flat template), 10 of 10 particles flagged"),
              std::string::npos)
        << r.output;
    EXPECT_EQ(r.output.find("Every available backend found the true pose"), std::string::npos) << r.output;
}

}  // namespace
