// `trnkit import-photos` and `trnkit localize --start-from-gps` as real processes: photos cut from a
// map we made, with GPS fixes at their centres, imported, then localized from the first fix with
// the fixes as a reference track; and the errors, each naming its flag or file.
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>

#include "cli_process.hpp"
#include "test_photos.hpp"
#include "trn/sim/map.hpp"

namespace fs = std::filesystem;
using trn::test::run_trnkit;
using trn::test::TestExif;

namespace {

#define EXPECT_HAS(text, part) EXPECT_NE(std::string(text).find(part), std::string::npos) << (text)

constexpr double kMpp = 0.5;
const trn::sim::GeoOrigin kOrigin{30.17, -98.09};

class PhotoCli : public testing::Test {
protected:
    void SetUp() override {
        dir_ = fs::temp_directory_path() / ("trn_photo_cli_" + std::to_string(::getpid()) + "_" +
                                            testing::UnitTest::GetInstance()->current_test_info()->name());
        fs::remove_all(dir_);
        fs::create_directories(dir_ / "photos");
        // A 600x400 map of smooth texture, and 5 photos cut from it along a line east, 20 px
        // (10 m) apart, 4x enlarged, GPS at each centre.
        cv::Mat noise(50, 75, CV_8UC1);
        cv::randu(noise, 0, 255);
        cv::resize(noise, map_, cv::Size(600, 400), 0, 0, cv::INTER_CUBIC);
        cv::imwrite(path("map.png"), map_);
        trn::sim::Map frame;
        frame.metres_per_pixel = kMpp, frame.origin = kOrigin;
        for (int i = 0; i < 5; ++i) {
            const int cx = 200 + 20 * i, cy = 200;
            cv::Mat crop = map_(cv::Rect(cx - 80, cy - 60, 160, 120)), big, colour;
            cv::resize(crop, big, cv::Size(640, 480), 0, 0, cv::INTER_CUBIC);
            cv::cvtColor(big, colour, cv::COLOR_GRAY2BGR);
            const trn::sim::LatLon ll = trn::sim::map_pixel_to_latlon(frame, cx, cy);
            char t[32];
            std::snprintf(t, sizeof t, "2020:05:01 10:00:%02d", 2 * i);
            trn::test::write_test_photo(path("photos/IMG_" + std::to_string(100 + i) + ".jpg"), colour,
                                        TestExif{}.set("Exif.Photo.DateTimeOriginal", t).gps(ll.latitude_deg, ll.longitude_deg));
        }
    }
    void TearDown() override { fs::remove_all(dir_); }
    std::string path(const std::string& name) const { return (dir_ / name).string(); }
    // 160 px frames spanning 160 map px = 80 m: the height that gives at hfov 68.87 deg.
    std::string import_args() const {
        return "import-photos " + path("photos") + " --out " + path("air") + " --width 160 --altitude-agl 58.34";
    }
    fs::path dir_;
    cv::Mat map_;
};

std::string read_text(const std::string& p) {
    std::ifstream f(p);
    std::stringstream ss;
    ss << f.rdbuf();
    return ss.str();
}

}  // namespace

TEST_F(PhotoCli, PhotosBecomeALocalizedFlightFromTheFirstGpsFix) {
    auto r = run_trnkit(import_args() + " --map " + path("map.png") + " --mpp 0.5 --map-origin 30.17,-98.09");
    ASSERT_EQ(r.code, 0) << r.output;
    EXPECT_HAS(r.output, "5 photos -> " + path("air") + ": 160x120 grey frames, Canon PowerShot SX260 HS, focal length 4.5 mm");
    EXPECT_HAS(r.output, "hfov 68.87 deg");
    EXPECT_HAS(r.output, "5 GPS fixes kept as Latitude,Longitude (camera GPS");
    EXPECT_HAS(r.output, "--start-from-gps RADIUS_M");

    r = run_trnkit("localize --dataset " + path("air") + " --odometry visual --start-from-gps 15 --backend cpu --no-plots --out " + path("loc"));
    ASSERT_EQ(r.code, 0) << r.output;
    EXPECT_HAS(r.output, "estimate to camera GPS: mean");
    EXPECT_HAS(r.output, "its fix lags the photo");
    EXPECT_HAS(r.output, "gps_track.csv: " + path("loc") + "/gps_track.csv");
    const nlohmann::json j = nlohmann::json::parse(read_text(path("loc/summary.json")));
    EXPECT_EQ(j["steps"], 5);
    EXPECT_EQ(j["init_radius_m"], 15);
    EXPECT_EQ(j["start"], "--start-from-gps (the first row's GPS fix)");
    EXPECT_NEAR(j["start_x"].get<double>(), 200, 0.05);  // the first fix placed through the map's origin
    EXPECT_NEAR(j["start_y"].get<double>(), 200, 0.05);
    EXPECT_EQ(j["gps_fixes_compared"], 5);
    EXPECT_TRUE(j["estimate_to_gps_mean_m"].is_number());
    EXPECT_HAS(j["gps_reference"].get<std::string>(), "not the truth");
    const std::string track = read_text(path("loc/gps_track.csv"));
    EXPECT_HAS(track, "frame,filename,gps_lat,gps_lon,gps_x,gps_y,estimate_x,estimate_y,estimate_to_gps_m\n0,frame_00000.png,");
    EXPECT_EQ(std::count(track.begin(), track.end(), '\n'), 6);
    const std::string marker = read_text(path("loc/.trnkit-output"));
    EXPECT_HAS(marker, "gps_track.csv");  // listed as localize's own, so a rerun replaces it
}

TEST_F(PhotoCli, ErrorsNameTheFlagOrTheFile) {
    auto r = run_trnkit("import-photos " + path("photos") + " --out " + path("air"));
    EXPECT_NE(r.code, 0);
    EXPECT_HAS(r.output, "--altitude-agl: required: the camera's height above the ground");
    EXPECT_FALSE(fs::exists(path("air")));

    trn::test::write_test_photo(path("photos/IMG_200.jpg"), cv::Mat(48, 64, CV_8UC3, cv::Scalar(9, 9, 9)),
                                TestExif{}.set("Exif.Image.Orientation", "3"));
    r = run_trnkit(import_args());
    EXPECT_NE(r.code, 0);
    EXPECT_HAS(r.output, "--ignore-orientation: " + path("photos/IMG_200.jpg") + ": EXIF Orientation 3");
    fs::remove(path("photos/IMG_200.jpg"));

    std::ofstream(path("photos/IMG_201.jpg")) << "GIF89a not a photo";
    r = run_trnkit(import_args());
    EXPECT_NE(r.code, 0);
    EXPECT_HAS(r.output, path("photos/IMG_201.jpg") + ": not a JPEG (the file is a GIF image)");
    fs::remove(path("photos/IMG_201.jpg"));

    r = run_trnkit(import_args() + " --map " + path("map.png"));
    EXPECT_NE(r.code, 0);
    EXPECT_HAS(r.output, "--mpp: required with --map");

    // Without a georeferenced map the fixes cannot be placed; without odometry in the folder only
    // visual odometry can run.
    ASSERT_EQ(run_trnkit(import_args()).code, 0);
    r = run_trnkit("localize --dataset " + path("air") + " --map " + path("map.png") + " --odometry visual --start-from-gps 15 --out " + path("loc"));
    EXPECT_NE(r.code, 0);
    EXPECT_HAS(r.output, "--mpp: required: " + path("air") + "/flight.json names no map resolution");
    r = run_trnkit("localize --dataset " + path("air") + " --map " + path("map.png") + " --mpp 0.5 --odometry visual --start-from-gps 15 --out " + path("loc"));
    EXPECT_NE(r.code, 0);
    EXPECT_HAS(r.output, "--start-from-gps: the map has no georeference");
    r = run_trnkit("localize --dataset " + path("air") + " --map " + path("map.png") + " --mpp 0.5 --start 200,200 --backend cpu --out " + path("loc"));
    EXPECT_NE(r.code, 0);
    EXPECT_HAS(r.output, "--odometry: " + path("air") + "/metadata.csv has no recorded odometry");
    r = run_trnkit("localize --dataset " + path("air") + " --map " + path("map.png") + " --mpp 0.5 --odometry visual --backend cpu --out " + path("loc"));
    EXPECT_NE(r.code, 0);
    EXPECT_HAS(r.output, "has no ground truth (empty MapX,MapY) in its first row; give --start (or --start-from-gps)");
    r = run_trnkit("localize --dataset " + path("air") + " --start 1,1 --start-from-gps 5 --map " + path("map.png") + " --mpp 0.5");
    EXPECT_NE(r.code, 0);
    EXPECT_HAS(r.output, "--start and --start-from-gps: give one of them, not both");

    // A camera not in the table.
    fs::remove_all(path("photos"));
    fs::create_directories(path("photos"));
    trn::test::write_test_photo(path("photos/a.jpg"), cv::Mat(48, 64, CV_8UC3, cv::Scalar(9, 9, 9)),
                                TestExif{}.set("Exif.Image.Model", "Mystery Cam"));
    r = run_trnkit(import_args());
    EXPECT_NE(r.code, 0);
    EXPECT_HAS(r.output, "--sensor-width-mm: required: the camera 'Mystery Cam'");
    r = run_trnkit(import_args() + " --sensor-width-mm 7.44");
    EXPECT_EQ(r.code, 0) << r.output;
    EXPECT_HAS(r.output, "sensor 7.44 mm wide (--sensor-width-mm)");
}
