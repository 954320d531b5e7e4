// Camera photos (issue 25 item 3): the EXIF reader (trn/io/photo.hpp) on photos whose EXIF we write
// ourselves, the reduction to grey frames, the import as an AIR folder (trn/sim/photo_import.hpp),
// the AIR format's empty column groups it relies on, and the import of realflight2's four photos
// against its frames (skipped visibly without TRN_SHARED_DATA).
#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>

#include "test_photos.hpp"
#include "trn/error.hpp"
#include "trn/field_error.hpp"
#include "trn/io/image_io.hpp"
#include "trn/io/photo.hpp"
#include "trn/sim/air_format.hpp"
#include "trn/sim/photo_import.hpp"
#include "../common/shared_data.hpp"

namespace fs = std::filesystem;
using trn::Error;
using trn::FieldError;
using trn::test::TestExif;
using trn::test::test_picture;
using trn::test::write_test_photo;

namespace {

class Photos : public testing::Test {
protected:
    void SetUp() override {
        dir_ = fs::temp_directory_path() / ("trn_photo_tests_" + std::to_string(::getpid()) + "_" +
                                            testing::UnitTest::GetInstance()->current_test_info()->name());
        fs::remove_all(dir_);
        fs::create_directories(dir_ / "photos");
    }
    void TearDown() override { fs::remove_all(dir_); }
    std::string path(const std::string& name) const { return (dir_ / name).string(); }
    std::string photo(const std::string& name, const TestExif& exif = {}, int w = 320, int h = 240, std::uint32_t seed = 1) {
        const std::string p = path("photos/" + name);
        write_test_photo(p, test_picture(w, h, seed), exif);
        return p;
    }
    trn::sim::PhotoImportOptions options() const {
        trn::sim::PhotoImportOptions o;
        o.photos = path("photos"), o.out = path("air"), o.altitude_agl_m = 60, o.width = 160;
        return o;
    }
    // The error of importing with `o` ("" when it works).
    std::string import_error(const trn::sim::PhotoImportOptions& o) {
        try {
            trn::sim::import_photos(o);
        } catch (const Error& e) {
            return e.what();
        }
        return "";
    }
    fs::path dir_;
};

std::string read_text(const std::string& p) {
    std::ifstream f(p, std::ios::binary);
    std::stringstream ss;
    ss << f.rdbuf();
    return ss.str();
}

std::string exif_error(const std::string& p) {
    try {
        trn::io::read_photo_exif(p);
    } catch (const Error& e) {
        return e.what();
    }
    return "";
}

#define EXPECT_HAS(text, part) EXPECT_NE(std::string(text).find(part), std::string::npos) << (text)

}  // namespace

TEST_F(Photos, ExifTagsAreRead) {
    const auto e = trn::io::read_photo_exif(photo("a.jpg", TestExif{}.set("Exif.Photo.SubSecTimeOriginal", "25")));
    EXPECT_EQ(e.width, 320);
    EXPECT_EQ(e.height, 240);
    EXPECT_EQ(e.make, "Canon");
    EXPECT_EQ(e.model, "Canon PowerShot SX260 HS");
    EXPECT_EQ(e.datetime_original, "2014:10:19 13:21:56");
    EXPECT_DOUBLE_EQ(e.time_s, 1413724916.25);  // 2014-10-19 13:21:56.25 as if UTC (EXIF states no zone)
    EXPECT_DOUBLE_EQ(e.focal_length_mm, 4.5);
    EXPECT_EQ(e.orientation, 1);
    ASSERT_TRUE(e.gps);
    EXPECT_NEAR(e.gps->latitude_deg, 30 + 10 / 60.0 + 14.904 / 3600, 1e-12);
    EXPECT_NEAR(e.gps->longitude_deg, -(98 + 5 / 60.0 + 22.308 / 3600), 1e-12);
    EXPECT_DOUBLE_EQ(e.gps->altitude_m, 380.5);
}

TEST_F(Photos, AbsentTagsAreAbsentAndAVoidFixIsNoFix) {
    TestExif t;
    for (const char* k : {"Exif.Photo.DateTimeOriginal", "Exif.Photo.FocalLength", "Exif.Image.Orientation", "Exif.GPSInfo.GPSLatitude",
                          "Exif.GPSInfo.GPSLatitudeRef", "Exif.GPSInfo.GPSLongitude", "Exif.GPSInfo.GPSLongitudeRef"})
        t.remove(k);
    const auto e = trn::io::read_photo_exif(photo("bare.jpg", t));
    EXPECT_TRUE(std::isnan(e.time_s));
    EXPECT_TRUE(std::isnan(e.focal_length_mm));
    EXPECT_EQ(e.orientation, 0);
    EXPECT_FALSE(e.gps);
    EXPECT_FALSE(trn::io::read_photo_exif(photo("void.jpg", TestExif{}.set("Exif.GPSInfo.GPSStatus", "V"))).gps);
    EXPECT_TRUE(std::isnan(trn::io::read_photo_exif(photo("blank.jpg", TestExif{}.set("Exif.Photo.DateTimeOriginal", "    :  :     :  :  "))).time_s));
}

TEST_F(Photos, MalformedTagsNameTheFileAndTheTag) {
    const std::pair<TestExif, std::string> cases[] = {
        {TestExif{}.set("Exif.Photo.DateTimeOriginal", "2014-10-19 13:21:56"), "EXIF DateTimeOriginal '2014-10-19 13:21:56' is not a date"},
        {TestExif{}.set("Exif.Photo.DateTimeOriginal", "2014:02:30 13:21:56"), "is no calendar date"},
        {TestExif{}.set("Exif.Photo.SubSecTimeOriginal", "2x"), "EXIF SubSecTimeOriginal '2x' is not digits"},
        {TestExif{}.set("Exif.Photo.FocalLength", "0/1"), "EXIF FocalLength 0/1 is not a focal length"},
        {TestExif{}.set("Exif.Photo.FocalLength", "45/0"), "EXIF FocalLength has a zero denominator"},
        {TestExif{}.set("Exif.Image.Orientation", "9"), "EXIF Orientation 9 is not one of 1..8"},
        {TestExif{}.set("Exif.GPSInfo.GPSLatitude", "30/1 10/1"), "EXIF GPSLatitude has 2 values, expected 3"},
        {TestExif{}.set("Exif.GPSInfo.GPSLatitude", "30/1 70/1 1/1"), "is not degrees, minutes (<= 60)"},
        {TestExif{}.set("Exif.GPSInfo.GPSLatitude", "95/1 0/1 0/1"), "EXIF GPSLatitude 95"},
        {TestExif{}.set("Exif.GPSInfo.GPSLatitudeRef", "X"), "EXIF GPSLatitudeRef 'X' is neither N nor S"},
        {TestExif{}.remove("Exif.GPSInfo.GPSLongitudeRef"), "EXIF GPSLongitude without GPSLongitudeRef"},
        {TestExif{}.remove("Exif.GPSInfo.GPSLongitude").remove("Exif.GPSInfo.GPSLongitudeRef"), "GPSLatitude without GPSLongitude"},
    };
    int i = 0;
    for (const auto& [exif, expected] : cases) {
        const std::string p = photo("bad" + std::to_string(i++) + ".jpg", exif);
        const std::string e = exif_error(p);
        EXPECT_HAS(e, p + ": ");
        EXPECT_HAS(e, expected);
    }
}

TEST_F(Photos, FilesThatAreNoJpegAreRefusedByName) {
    const std::string png = path("photos/x.jpg");
    ASSERT_TRUE(cv::imwrite(png + ".png", test_picture(32, 32, 2)));
    fs::rename(png + ".png", png);  // a PNG under a .jpg name: the contents decide
    EXPECT_HAS(exif_error(png), png + ": not a JPEG (the file is a PNG image)");
    std::ofstream(path("photos/notes.txt")) << "flight notes\n";
    EXPECT_HAS(exif_error(path("photos/notes.txt")), "notes.txt: not a JPEG (the file is of an unknown kind)");
    std::ofstream(path("photos/empty.jpg")).close();
    EXPECT_HAS(exif_error(path("photos/empty.jpg")), "empty.jpg: empty file, not a JPEG");
    // A JPEG cut short, and one whose bytes after the header are noise.
    const std::string good = read_text(photo("good.jpg"));
    std::ofstream(path("photos/cut.jpg"), std::ios::binary) << good.substr(0, 40);
    EXPECT_HAS(exif_error(path("photos/cut.jpg")), "cut.jpg: corrupt");
    std::string noise = good.substr(0, 4);
    for (int k = 0; k < 5000; ++k) noise += static_cast<char>((k * 7919) & 0xFF);
    std::ofstream(path("photos/noise.jpg"), std::ios::binary) << noise;
    EXPECT_HAS(exif_error(path("photos/noise.jpg")), "noise.jpg: corrupt");
    try {
        trn::io::load_photo_gray(path("photos/noise.jpg"), 100);
        ADD_FAILURE() << "decoded noise";
    } catch (const Error& e) {
        EXPECT_HAS(e.what(), "noise.jpg: ");
    }
    EXPECT_HAS(exif_error(path("photos/absent.jpg")), "absent.jpg: no such file");
    EXPECT_HAS(exif_error(path("photos")), "photos: is a folder, not a regular file");
}

TEST_F(Photos, FramesAreAreaAveragedColourThenGrey) {
    const cv::Mat picture = test_picture(800, 600, 3);
    const std::string p = path("photos/big.jpg");
    write_test_photo(p, picture, TestExif{}.set("Exif.Image.Orientation", "6"));
    const trn::GrayImage g = trn::io::load_photo_gray(p, 455);
    EXPECT_EQ(g.width, 455);
    EXPECT_EQ(g.height, 341);  // 600 * 455 / 800 = 341.25
    // The same steps by hand on the decoded pixels, stored orientation (EXIF's 6 is not applied).
    cv::Mat decoded = cv::imread(p, cv::IMREAD_COLOR | cv::IMREAD_IGNORE_ORIENTATION), reduced, grey;
    cv::resize(decoded, reduced, cv::Size(455, 341), 0, 0, cv::INTER_AREA);
    cv::cvtColor(reduced, grey, cv::COLOR_BGR2GRAY);
    ASSERT_EQ(grey.cols, g.width);
    int differ = 0;
    for (int y = 0; y < g.height; ++y)
        for (int x = 0; x < g.width; ++x) differ += grey.at<std::uint8_t>(y, x) != g.pixels[std::size_t(y) * g.width + x];
    EXPECT_EQ(differ, 0);
    EXPECT_EQ(trn::io::load_photo_gray(p, 2000).width, 800);  // never enlarged
    // 100 px of 800: decoded at 1/8 in the DCT domain (block means, 100x75), nothing left to average.
    const trn::GrayImage small = trn::io::load_photo_gray(p, 100);
    cv::Mat eighth = cv::imread(p, cv::IMREAD_REDUCED_COLOR_8 | cv::IMREAD_IGNORE_ORIENTATION), grey8;
    ASSERT_EQ(eighth.cols, 100);
    cv::cvtColor(eighth, grey8, cv::COLOR_BGR2GRAY);
    ASSERT_EQ(small.width, 100);
    ASSERT_EQ(small.height, 75);
    differ = 0;
    for (int y = 0; y < small.height; ++y)
        for (int x = 0; x < small.width; ++x) differ += grey8.at<std::uint8_t>(y, x) != small.pixels[std::size_t(y) * small.width + x];
    EXPECT_EQ(differ, 0);
}

TEST(AirFormatGroups, EmptyGroupsAreNaNAndHalfGroupsAreBroken) {
    const std::string header =
        "Filename,Latitude,Longitude,RelativeAltitude,ImuX,ImuY,ImuZ,ImuW,PoseX,PoseY,PoseZ,OrientationX,OrientationY,"
        "OrientationZ,OrientationW,MapX,MapY,SvoX,SvoY,SvoZ,Photo\n";
    std::stringstream in(header + "frame_00000.png,30.1,-98.1,60,,,,,,,,,,,,,,,,,IMG_1.jpg\n");
    trn::sim::AirMetadataParser p(in, "m.csv");
    trn::sim::AirRecord r;
    ASSERT_TRUE(p.next(r));
    EXPECT_DOUBLE_EQ(r.latitude_deg, 30.1);
    EXPECT_DOUBLE_EQ(r.relative_altitude_m, 60);
    for (double v : {r.imu.x, r.imu.w, r.pose_m.x, r.pose_m.z, r.orientation.y, r.map_x, r.map_y, r.svo_m.x, r.svo_m.z}) EXPECT_TRUE(std::isnan(v));
    EXPECT_TRUE(std::isnan(trn::sim::heading_from_quaternion(r.imu)));           // no compass
    EXPECT_EQ(trn::sim::roll_pitch_from_quaternion(r.imu).roll_rad, 0);          // taken as level
    auto error_of = [&](const std::string& row) {
        std::stringstream s(header + row);
        try {
            trn::sim::AirMetadataParser q(s, "m.csv");
            while (q.next(r)) {
            }
        } catch (const Error& e) {
            return std::string(e.what());
        }
        return std::string();
    };
    EXPECT_HAS(error_of("a.png,30.1,-98.1,60,0,0,,1,,,,,,,,,,,,,x\n"), "m.csv:2: ImuZ '' is not a number (ImuX..ImuW are given all or left all empty)");
    EXPECT_HAS(error_of("a.png,,-98.1,60,,,,,,,,,,,,,,,,,x\n"), "Latitude '' is not a number (Latitude,Longitude");
    EXPECT_HAS(error_of("a.png,30.1,-98.1,,,,,,,,,,,,,,,,,,x\n"), "RelativeAltitude '' is not a number");  // never optional
    EXPECT_EQ(error_of("a.png,,,60,,,,,,,,,,,,,,,,,x\n"), "");

    // The writer writes NaN as empty cells and refuses a group partly NaN.
    const fs::path dir = fs::temp_directory_path() / ("trn_air_groups_" + std::to_string(::getpid()));
    fs::remove_all(dir);
    {
        trn::sim::AirWriter w(dir.string(), {"Photo"});
        trn::sim::AirRecord rec;
        rec.filename = "frame_00000.png", rec.latitude_deg = 30.5, rec.longitude_deg = -98, rec.relative_altitude_m = 60;
        rec.imu = rec.orientation = {NAN, NAN, NAN, NAN};
        rec.pose_m = rec.svo_m = {NAN, NAN, NAN};
        rec.map_x = rec.map_y = NAN;
        w.write(rec, {}, {"IMG, 1.jpg"});
        rec.filename = "frame_00001.png", rec.imu.w = 1;
        EXPECT_THROW(w.write(rec, {}, {"b"}), Error);
        EXPECT_THROW(w.write(rec, {}, {}), Error);  // one value per extra column
        w.close();
    }
    const std::string csv = read_text((dir / "metadata.csv").string());
    EXPECT_HAS(csv, "SvoZ,Photo\nframe_00000.png,30.5000000000,-98.0000000000,60.0000,,,,,,,,,,,,,,,,,\"IMG, 1.jpg\"\n");
    fs::remove_all(dir);
}

TEST_F(Photos, ImportOrdersByTimeAndWritesAnAirFolderLocalizeReads) {
    // Names out of time order; two photos in the same second (ordered by name).
    photo("IMG_3.jpg", TestExif{}.set("Exif.Photo.DateTimeOriginal", "2014:10:19 13:22:00").gps(30.2, -98.2), 320, 240, 3);
    photo("IMG_1.jpg", TestExif{}.set("Exif.Photo.DateTimeOriginal", "2014:10:19 13:21:58").gps(30.1, -98.1), 320, 240, 1);
    photo("IMG_2.jpg", TestExif{}.set("Exif.Photo.DateTimeOriginal", "2014:10:19 13:21:58").gps(30.15, -98.15), 320, 240, 2);
    photo("IMG_0.jpg", TestExif{}.set("Exif.Photo.DateTimeOriginal", "2014:10:19 13:22:02").remove("Exif.GPSInfo.GPSLatitude")
                           .remove("Exif.GPSInfo.GPSLatitudeRef").remove("Exif.GPSInfo.GPSLongitude").remove("Exif.GPSInfo.GPSLongitudeRef"),
          320, 240, 4);
    std::ofstream(path("photos/.DS_Store")) << "hidden";  // hidden files and sub-folders are not photos
    fs::create_directories(path("photos/thumbs"));
    const trn::sim::PhotoImportResult r = trn::sim::import_photos(options());
    ASSERT_EQ(r.photos.size(), 4u);
    EXPECT_EQ(r.photos[0].photo, "IMG_1.jpg");
    EXPECT_EQ(r.photos[1].photo, "IMG_2.jpg");
    EXPECT_EQ(r.photos[2].photo, "IMG_3.jpg");
    EXPECT_EQ(r.photos[3].photo, "IMG_0.jpg");
    EXPECT_EQ(r.photos[3].frame, "frame_00003.png");
    EXPECT_DOUBLE_EQ(r.photos[3].time_s, 4);
    EXPECT_DOUBLE_EQ(r.fps, 0.75);  // 3 intervals in 4 s
    EXPECT_EQ(r.gps_fixes, 3u);
    EXPECT_NEAR(r.hfov_deg, 2 * std::atan(6.17 / 9) * 180 / M_PI, 1e-9);
    EXPECT_NEAR(r.hfov_deg, 68.87, 0.01);
    EXPECT_EQ(r.frame_width, 160);
    EXPECT_EQ(r.frame_height, 120);
    std::string notes;
    for (const auto& n : r.notes) notes += n + "\n";
    EXPECT_HAS(notes, "ordered by EXIF DateTimeOriginal");
    EXPECT_HAS(notes, "1 photos share their EXIF time");
    EXPECT_HAS(notes, "1 of 4 photos have no GPS fix (first: IMG_0.jpg)");

    trn::sim::AirReader reader(path("air"));
    trn::sim::AirRecord rec;
    std::vector<trn::sim::AirRecord> rows;
    while (reader.next(rec)) rows.push_back(rec);
    ASSERT_EQ(rows.size(), 4u);
    EXPECT_EQ(rows[0].filename, "frame_00000.png");
    EXPECT_NEAR(rows[0].latitude_deg, 30.1, 1e-8);
    EXPECT_NEAR(rows[2].longitude_deg, -98.2, 1e-8);
    EXPECT_TRUE(std::isnan(rows[3].latitude_deg));
    EXPECT_DOUBLE_EQ(rows[1].relative_altitude_m, 60);
    EXPECT_TRUE(std::isnan(rows[1].map_x) && std::isnan(rows[1].svo_m.x) && std::isnan(rows[1].imu.w) && std::isnan(rows[1].pose_m.x));
    EXPECT_EQ(reader.load_image(rows[2]).width, 160);
    const std::string csv = read_text(path("air/metadata.csv"));
    EXPECT_HAS(csv, ",Photo,DateTimeOriginal,TimeS\n");
    EXPECT_HAS(csv, ",IMG_3.jpg,2014:10:19 13:22:00,2.000\n");
    const trn::sim::FlightInfo info = trn::sim::read_flight_info(path("air/flight.json"));
    EXPECT_EQ(info.latlon_source, trn::sim::kLatLonCameraGps);
    EXPECT_EQ(info.map_file, "");
    EXPECT_EQ(info.metres_per_pixel, 0);  // no map named: localize --map / --mpp give it
    EXPECT_EQ(info.frames, 4u);
    EXPECT_NEAR(info.camera.hfov_deg, 68.87, 0.01);
    EXPECT_EQ(info.camera.width, 160);
    EXPECT_TRUE(fs::exists(path("air/.trnkit-output")));
    // A rerun replaces its own earlier output; a folder of someone else's is refused.
    EXPECT_EQ(import_error(options()), "");
    fs::create_directories(path("mine"));
    std::ofstream(path("mine/notes.txt")) << "mine";
    auto o = options();
    o.out = path("mine");
    EXPECT_HAS(import_error(o), "not empty");
    EXPECT_EQ(read_text(path("mine/notes.txt")), "mine");
}

TEST_F(Photos, MissingTagsAndOddPhotosAreClearErrors) {
    photo("a.jpg");
    auto o = options();
    o.altitude_agl_m = NAN;
    EXPECT_HAS(import_error(o), "altitude_agl_m: required: the camera's height above the ground in metres (EXIF GPS altitude is above sea level");
    EXPECT_FALSE(fs::exists(path("air")));

    photo("b.jpg", TestExif{}.remove("Exif.Photo.DateTimeOriginal"));
    EXPECT_HAS(import_error(options()), path("photos/b.jpg") + ": EXIF DateTimeOriginal is missing");
    photo("b.jpg", TestExif{}.remove("Exif.Photo.FocalLength"));
    EXPECT_HAS(import_error(options()), path("photos/b.jpg") + ": EXIF FocalLength is missing");
    photo("b.jpg", TestExif{}.set("Exif.Photo.FocalLength", "50/10"));
    EXPECT_HAS(import_error(options()), "b.jpg: EXIF FocalLength 5 mm differs from a.jpg's 4.5 mm");
    photo("b.jpg", TestExif{}.set("Exif.Image.Model", "Other Camera"));
    EXPECT_HAS(import_error(options()), "import one camera's photos at a time");
    photo("b.jpg", TestExif{}.set("Exif.Image.Orientation", "6"));
    const std::string rotated = import_error(options());
    EXPECT_HAS(rotated, "ignore_orientation: " + path("photos/b.jpg") + ": EXIF Orientation 6");
    EXPECT_HAS(rotated, "trnkit does not rotate frames by it");
    o = options();
    o.ignore_orientation = true;
    EXPECT_EQ(import_error(o), "");
    std::ofstream(path("photos/c.png")) << "\x89PNG\r\n";
    EXPECT_HAS(import_error(o), path("photos/c.png") + ": not a JPEG (the file is a PNG image)");
    fs::remove(path("photos/c.png"));
    EXPECT_FALSE(fs::exists(path("air/c.png")));

    // A camera not in the table: its sensor width is required.
    fs::remove_all(path("photos"));
    fs::create_directories(path("photos"));
    photo("a.jpg", TestExif{}.set("Exif.Image.Model", "Mystery Cam 3000"));
    EXPECT_HAS(import_error(options()), "sensor_width_mm: required: the camera 'Mystery Cam 3000' of " + path("photos") + "/a.jpg is not in trnkit's table");
    o = options();
    o.sensor_width_mm = 13.2;
    const auto r = trn::sim::import_photos(o);
    EXPECT_NEAR(r.hfov_deg, 2 * std::atan(13.2 / 9) * 180 / M_PI, 1e-9);
    EXPECT_EQ(r.sensor_width_source, "sensor_width_mm");
    fs::remove_all(path("photos"));
    fs::create_directories(path("photos"));
    EXPECT_HAS(import_error(options()), "photos: " + path("photos") + ": no photos in the folder");
}

TEST_F(Photos, AMapNamedAtImportIsFoundFromTheFolder) {
    photo("a.jpg");
    ASSERT_TRUE(cv::imwrite(path("map.png"), cv::Mat(100, 100, CV_8UC1, cv::Scalar(128))));
    auto o = options();
    o.map = path("map.png");
    EXPECT_HAS(import_error(o), "metres_per_pixel: required with `map`");
    o.metres_per_pixel = 0.27;
    o.map_origin = trn::sim::GeoOrigin{30.17, -98.09};
    EXPECT_EQ(import_error(o), "");
    const trn::sim::FlightInfo info = trn::sim::read_flight_info(path("air/flight.json"));
    EXPECT_EQ(info.map_file, "../map.png");
    EXPECT_DOUBLE_EQ(info.metres_per_pixel, 0.27);
    ASSERT_TRUE(info.origin);
    EXPECT_DOUBLE_EQ(info.origin->latitude_deg, 30.17);
    o = options();
    o.map_origin = trn::sim::GeoOrigin{30.17, -98.09};
    EXPECT_HAS(import_error(o), "map: required with `map_origin`");
}

TEST(CameraSensors, TheTableKnowsTheRealFlightsCamera) {
    EXPECT_DOUBLE_EQ(trn::sim::known_sensor_width_mm("Canon PowerShot SX260 HS"), 6.17);
    EXPECT_DOUBLE_EQ(trn::sim::known_sensor_width_mm("fc6310"), 13.2);  // case does not matter
    EXPECT_TRUE(std::isnan(trn::sim::known_sensor_width_mm("Mystery Cam 3000")));
    for (const auto& s : trn::sim::known_camera_sensors()) EXPECT_TRUE(s.sensor_width_mm > 1 && s.sensor_width_mm < 40) << s.model;
}

// realflight2's four photos against the frames made from them (area average to 455x341, then grey).
TEST(RealFlight2Photos, ImportMatchesTheFramesMadeFromThem) {
    const fs::path data = trn::test::shared_data("realflight2");
    if (data.empty() || !fs::is_directory(data / "photos") || !fs::is_directory(data / "frames"))
        GTEST_SKIP() << "TRN_SHARED_DATA/realflight2/photos not found: realflight2 unavailable";
    const fs::path out = fs::temp_directory_path() / ("trn_realflight2_import_" + std::to_string(::getpid()));
    fs::remove_all(out);
    trn::sim::PhotoImportOptions o;
    o.photos = (data / "photos").string(), o.out = out.string(), o.altitude_agl_m = 60;  // default width 455
    const trn::sim::PhotoImportResult r = trn::sim::import_photos(o);
    ASSERT_EQ(r.photos.size(), 4u);
    EXPECT_EQ(r.camera, "Canon PowerShot SX260 HS");
    EXPECT_NEAR(r.hfov_deg, 68.87, 0.01);
    EXPECT_EQ(r.gps_fixes, 4u);
    // Four of 32 photos taken ~2 s apart (frames 0, 1, 16, 31): the mean rate over the four.
    std::printf("realflight2 photo times: %.0f %.0f %.0f %.0f s\n", r.photos[0].time_s, r.photos[1].time_s, r.photos[2].time_s, r.photos[3].time_s);
    EXPECT_EQ(r.photos[0].time_s, 0);
    EXPECT_GT(r.photos[1].time_s, 0);
    EXPECT_NEAR(r.fps, 3 / r.photos[3].time_s, 1e-12);
    const char* frames[] = {"frame_00000.png", "frame_00001.png", "frame_00016.png", "frame_00031.png"};
    for (int i = 0; i < 4; ++i) {
        const trn::GrayImage mine = trn::load_gray((out / r.photos[i].frame).string());
        const trn::GrayImage theirs = trn::load_gray((data / "frames" / frames[i]).string());
        ASSERT_EQ(mine.width, 455);
        ASSERT_EQ(mine.height, 341);
        ASSERT_EQ(theirs.width, mine.width);
        ASSERT_EQ(theirs.height, mine.height);
        int max_diff = 0;
        double sum = 0;
        for (std::size_t k = 0; k < mine.pixels.size(); ++k) {
            const int diff = std::abs(int(mine.pixels[k]) - int(theirs.pixels[k]));
            max_diff = std::max(max_diff, diff), sum += diff;
        }
        const double mean = sum / mine.pixels.size();
        std::printf("realflight2 %s (%s): max |difference| %d, mean %.4f grey levels\n", frames[i], r.photos[i].photo.c_str(), max_diff, mean);
        // Measured: max 24, 22, 21, 10 (single pixels on one row, where the two area averages' row
        // boundaries round apart), mean 0.0046, 0.0046, 0.0034, 0.0033.
        EXPECT_LE(max_diff, 32) << frames[i];
        EXPECT_LE(mean, 0.02) << frames[i];
    }
    fs::remove_all(out);
}
