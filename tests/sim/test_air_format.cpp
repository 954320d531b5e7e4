// AIR dataset writer / reader: round trip, quoting, column order, malformed rows by line number,
// and a fuzzed reader that must either parse or throw trn::Error.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <filesystem>
#include <sstream>

#include "sim_test_maps.hpp"
#include "trn/detail/angles.hpp"
#include "trn/sim/air_format.hpp"

namespace trn::sim {
namespace {

std::string temp_folder(const std::string& name) {
    const auto p = std::filesystem::temp_directory_path() / ("trn_sim_" + name + "_" + std::to_string(::getpid()));
    std::filesystem::remove_all(p);
    return p.string();
}

const char* kHeader =
    "Filename,Latitude,Longitude,RelativeAltitude,ImuX,ImuY,ImuZ,ImuW,PoseX,PoseY,PoseZ,OrientationX,OrientationY,"
    "OrientationZ,OrientationW,MapX,MapY,SvoX,SvoY,SvoZ\n";
const char* kRow = "a.png,47.1,8.2,200,0,0,0.1,0.99,1,2,200,0,0,0.1,0.99,10.5,20.25,1.1,2.2,200.5\n";

TEST(AirFormat, WriterReaderRoundTripWithImages) {
    const Map& map = testing::urban_map();
    FlightConfig cfg;
    cfg.scenario = find_scenario("UR-200");
    cfg.frames = 4;
    FlightSimulator sim(map, cfg);
    const std::string dir = temp_folder("roundtrip");
    std::vector<AirRecord> written;
    std::vector<GrayImage> images;
    {
        AirWriter w(dir);
        FlightFrame f;
        while (sim.next(f)) {
            written.push_back(make_air_record(f, "img " + std::to_string(f.index) + ",x.png"));  // needs quoting
            images.push_back(f.image);
            w.write(written.back(), f.image.view());
        }
        w.close();
    }
    AirReader r(dir);
    AirRecord rec;
    std::size_t i = 0;
    while (r.next(rec)) {
        ASSERT_LT(i, written.size());
        const AirRecord& e = written[i];
        EXPECT_EQ(rec.filename, e.filename);
        EXPECT_NEAR(rec.latitude_deg, e.latitude_deg, 1e-9);
        EXPECT_NEAR(rec.longitude_deg, e.longitude_deg, 1e-9);
        EXPECT_NEAR(rec.map_x, e.map_x, 1e-3);
        EXPECT_NEAR(rec.map_y, e.map_y, 1e-3);
        EXPECT_NEAR(rec.svo_m.x, e.svo_m.x, 1e-4);
        EXPECT_NEAR(rec.pose_m.y, e.pose_m.y, 1e-4);
        EXPECT_NEAR(rec.orientation.z, e.orientation.z, 1e-8);
        EXPECT_NEAR(rec.imu.w, e.imu.w, 1e-8);
        EXPECT_NEAR(rec.relative_altitude_m, 200, 1e-9);
        EXPECT_EQ(r.load_image(rec).pixels, images[i].pixels);  // PNG is lossless
        ++i;
    }
    EXPECT_EQ(i, written.size());
    std::filesystem::remove_all(dir);
}

TEST(AirFormat, FlightInfoRoundTrip) {
    const std::string dir = temp_folder("info");
    std::filesystem::create_directories(dir);
    FlightInfo info;
    info.scenario = "FC-300";
    info.map_file = "map.png";
    info.metres_per_pixel = 0.5;
    info.origin = GeoOrigin{46.5, 7.25};
    info.camera = {640, 480, 72};
    info.map_year = 2008;
    info.rendered_year = 2014;
    write_flight_info(dir + "/flight.json", info);
    const FlightInfo back = read_flight_info(dir + "/flight.json");
    EXPECT_EQ(back.scenario, "FC-300");
    EXPECT_DOUBLE_EQ(back.metres_per_pixel, 0.5);
    ASSERT_TRUE(back.origin.has_value());
    EXPECT_DOUBLE_EQ(back.origin->longitude_deg, 7.25);
    EXPECT_DOUBLE_EQ(back.camera.hfov_deg, 72);
    EXPECT_EQ(back.rendered_year, 2014);
    EXPECT_THROW(read_flight_info(dir + "/missing.json"), Error);
    std::filesystem::remove_all(dir);
}

TEST(AirFormat, QuaternionHeadingRoundTrip) {
    for (double h : {0.0, 0.5, 1.5707963, 3.0, -2.0}) EXPECT_NEAR(wrap_angle(heading_from_quaternion(attitude_quaternion(h)) - h), 0, 1e-12);
    // Heading north (0) is ENU yaw +90 degrees: a quarter turn about z.
    const Quaternion q = attitude_quaternion(0);
    EXPECT_NEAR(q.z, std::sqrt(0.5), 1e-12);
    EXPECT_NEAR(q.w, std::sqrt(0.5), 1e-12);
}

// Roll and pitch come back from the quaternion the simulator writes (what a real flight's ImuX..W
// carry), at any heading, and give the tilt of the optical axis.
TEST(AirFormat, QuaternionRollPitchRoundTrip) {
    for (double h : {0.0, 1.0, -2.5})
        for (double roll : {0.0, 0.1, -0.3})
            for (double pitch : {0.0, -0.2, 0.25}) {
                const RollPitch rp = roll_pitch_from_quaternion(attitude_quaternion(h, roll, pitch));
                EXPECT_NEAR(rp.roll_rad, roll, 1e-12) << h << " " << roll << " " << pitch;
                EXPECT_NEAR(rp.pitch_rad, pitch, 1e-12) << h << " " << roll << " " << pitch;
            }
    Quaternion scaled = attitude_quaternion(0.3, 0.2, 0);  // the reader allows lengths 0.9-1.1
    scaled.x *= 1.05, scaled.y *= 1.05, scaled.z *= 1.05, scaled.w *= 1.05;
    EXPECT_NEAR(roll_pitch_from_quaternion(scaled).roll_rad, 0.2, 1e-12);
    EXPECT_NEAR(tilt_from_nadir(0.2, 0), 0.2, 1e-12);
    EXPECT_NEAR(tilt_from_nadir(0, -0.2), 0.2, 1e-12);
    EXPECT_NEAR(std::cos(tilt_from_nadir(0.1, 0.2)), std::cos(0.1) * std::cos(0.2), 1e-12);
}

TEST(AirFormat, ReaderAcceptsQuotesAnyColumnOrderExtraColumnsCrlfAndBom) {
    std::stringstream in;
    in << "\xEF\xBB\xBF" << "Extra,MapY,MapX,Filename,Latitude,Longitude,RelativeAltitude,ImuX,ImuY,ImuZ,ImuW,PoseX,PoseY,PoseZ,"
       << "OrientationX,OrientationY,OrientationZ,OrientationW,SvoX,SvoY,SvoZ\r\n"
       << "zzz,2,1,\"my \"\"odd\"\", file.png\",47,8,200,0,0,0,1,0,0,200,0,0,0,1,0,0,200\r\n"
       << "\n"
       << "q, 4 , 3 ,plain.png,47,8,200,0,0,0,1,0,0,200,0,0,0,1,0,0,200\n";
    AirMetadataParser p(in, "mem.csv");
    AirRecord r;
    ASSERT_TRUE(p.next(r));
    EXPECT_EQ(r.filename, "my \"odd\", file.png");
    EXPECT_EQ(r.map_x, 1);
    EXPECT_EQ(r.map_y, 2);
    ASSERT_TRUE(p.next(r));
    EXPECT_EQ(p.line(), 4);
    EXPECT_EQ(r.filename, "plain.png");
    EXPECT_EQ(r.map_x, 3);
    EXPECT_FALSE(p.next(r));
}

std::string error_of(const std::string& text) {
    std::stringstream in(text);
    try {
        AirMetadataParser p(in, "m.csv");
        AirRecord r;
        while (p.next(r)) {
        }
    } catch (const Error& e) {
        return e.what();
    }
    return "";
}

TEST(AirFormat, MalformedRowsAreReportedByLineNumber) {
    const std::string h = kHeader, ok = kRow, ok2 = std::string("b") + (kRow + 1);
    EXPECT_EQ(error_of(h + ok + ok2), "");
    EXPECT_NE(error_of(h + ok + "b.png,47,8\n").find("m.csv:3: expected 20 fields"), std::string::npos);
    EXPECT_NE(error_of(h + ok + ok2 + "c.png,north,8.2,200,0,0,0.1,0.99,1,2,200,0,0,0.1,0.99,10.5,20.25,1.1,2.2,200.5\n")
                  .find("m.csv:4: Latitude 'north' is not a number"),
              std::string::npos);
    EXPECT_NE(error_of(h + "\"a.png,47,8\n").find("m.csv:2: unterminated quoted field"), std::string::npos);
    EXPECT_NE(error_of(h + ",47.1,8.2,200,0,0,0.1,0.99,1,2,200,0,0,0.1,0.99,10.5,20.25,1.1,2.2,200.5\n").find("m.csv:2: Filename is empty"),
              std::string::npos);
    EXPECT_NE(error_of(h + "a.png,nan,8.2,200,0,0,0.1,0.99,1,2,200,0,0,0.1,0.99,10.5,20.25,1.1,2.2,200.5\n").find("not finite"),
              std::string::npos);
    EXPECT_NE(error_of("Filename,Latitude\n").find("m.csv:1: header lacks the column Longitude"), std::string::npos);
    EXPECT_NE(error_of("").find("empty file"), std::string::npos);
    EXPECT_THROW(AirReader(temp_folder("nothing_here")), Error);
}

// A row of kRow's values with one column replaced (by name).
std::string row_with(const std::string& column, const std::string& value, const std::string& filename = "a.png") {
    std::vector<std::string> fields;
    std::stringstream ss(std::string(kRow).substr(0, std::string(kRow).size() - 1));
    for (std::string f; std::getline(ss, f, ',');) fields.push_back(f);
    fields[0] = filename;
    const auto& names = air_columns();
    fields[std::find(names.begin(), names.end(), column) - names.begin()] = value;
    std::string out;
    for (const auto& f : fields) out += (out.empty() ? "" : ",") + f;
    return out + "\n";
}

TEST(AirFormat, ImplausibleNumbersAreReportedByLineAndColumn) {
    const std::string h = kHeader;
    EXPECT_EQ(error_of(h + row_with("MapX", "1e6")), "");
    EXPECT_NE(error_of(h + row_with("MapX", "1e300")).find("m.csv:2: MapX 1e+300 is outside [-1e+07, 1e+07]"), std::string::npos);
    EXPECT_NE(error_of(h + kRow + row_with("Latitude", "91", "b.png")).find("m.csv:3: Latitude 91 is outside [-90, 90]"),
              std::string::npos);
    EXPECT_NE(error_of(h + row_with("Longitude", "-181")).find("Longitude -181 is outside [-180, 180]"), std::string::npos);
    EXPECT_NE(error_of(h + row_with("SvoY", "-3e9")).find("m.csv:2: SvoY -3e+09 is outside"), std::string::npos);
    EXPECT_NE(error_of(h + row_with("RelativeAltitude", "1e12")).find("RelativeAltitude 1e+12 is outside"), std::string::npos);
    // An all-zero or scaled quaternion has no attitude: heading_from_quaternion would invent one.
    EXPECT_NE(error_of(h + row_with("OrientationW", "5")).find("m.csv:2: OrientationX,OrientationY,OrientationZ,OrientationW has length 5"),
              std::string::npos);
    std::stringstream in(h + "a.png,47.1,8.2,200,0,0,0,0,1,2,200,0,0,0.1,0.99,10.5,20.25,1.1,2.2,200.5\n");
    AirMetadataParser p(in, "q.csv");
    AirRecord r;
    try {
        p.next(r);
        ADD_FAILURE() << "a zero IMU quaternion was accepted";
    } catch (const Error& e) {
        EXPECT_NE(std::string(e.what()).find("q.csv:2: ImuX,ImuY,ImuZ,ImuW has length 0"), std::string::npos) << e.what();
    }
}

TEST(AirFormat, DuplicatedOrShuffledRowsAreRefused) {
    const std::string h = kHeader;
    auto named = [](const std::string& f) { return row_with("MapX", "10", f); };
    EXPECT_EQ(error_of(h + named("frame_000009.png") + named("frame_000010.png") + named("frame_1000000000000000000000001.png")), "");
    EXPECT_EQ(error_of(h + named("b.png") + named("a.png")), "");  // no frame numbers: file order is all there is
    EXPECT_NE(error_of(h + named("x.png") + named("y.png") + named("x.png")).find("m.csv:4: x.png is listed again (first on line 2)"),
              std::string::npos);
    EXPECT_NE(error_of(h + named("f_7.png") + named("f_0005.png")).find("m.csv:3: f_0005.png comes after f_7.png"), std::string::npos);
    EXPECT_NE(error_of(h + named("f_7.png") + named("g_007.jpg")).find("m.csv:3: g_007.jpg comes after f_7.png"), std::string::npos);
    EXPECT_NE(error_of(h + named("f_99999999999999999999.png") + named("f_99999999999999999998.png")).find("comes after"),
              std::string::npos);  // beyond 64 bits, still ordered
}

// TimeS (optional, issue 42): when each frame was taken, read where the header has it; empty is
// unknown; it must not go backwards and must be a number.
TEST(AirFormat, OptionalTimeColumnIsReadAndChecked) {
    const std::string h = std::string(kHeader).substr(0, std::string(kHeader).size() - 1) + ",TimeS\n";
    auto timed = [](const std::string& f, const std::string& t) { std::string r = row_with("MapX", "10", f); return r.substr(0, r.size() - 1) + "," + t + "\n"; };
    std::stringstream in(h + timed("f_1.png", "0") + timed("f_2.png", "5.5") + timed("f_3.png", "") + timed("f_4.png", "45"));
    AirMetadataParser p(in, "t.csv");
    AirRecord r;
    std::vector<double> times;
    while (p.next(r)) times.push_back(r.time_s);
    ASSERT_EQ(times.size(), 4u);
    EXPECT_EQ(times[0], 0.0);
    EXPECT_EQ(times[1], 5.5);
    EXPECT_TRUE(std::isnan(times[2]));  // unknown, not zero
    EXPECT_EQ(times[3], 45.0);
    std::stringstream untimed(std::string(kHeader) + kRow);  // no column: NaN
    AirMetadataParser q(untimed, "u.csv");
    ASSERT_TRUE(q.next(r));
    EXPECT_TRUE(std::isnan(r.time_s));
    EXPECT_NE(error_of(h + timed("f_1.png", "10") + timed("f_2.png", "9.5")).find("m.csv:3: TimeS 9.5 is before the previous row's 10"),
              std::string::npos);
    EXPECT_NE(error_of(h + timed("f_1.png", "noon")).find("m.csv:2: TimeS 'noon' is not a time in seconds"), std::string::npos);
    EXPECT_NE(error_of(h + timed("f_1.png", "inf")).find("TimeS 'inf' is not a time"), std::string::npos);
    EXPECT_NE(error_of(h + timed("f_1.png", "1e300")).find("TimeS '1e300' is not a time"), std::string::npos);
    EXPECT_NE(error_of(std::string(kHeader).substr(0, std::string(kHeader).size() - 1) + ",TimeS,TimeS\n").find("column TimeS appears twice"),
              std::string::npos);
}

TEST(AirFormat, ReaderRefusesAFolderWithOnlyAHeader) {
    const std::string dir = temp_folder("header_only");
    std::filesystem::create_directories(dir);
    std::ofstream(dir + "/metadata.csv") << kHeader;
    AirReader reader(dir);
    AirRecord r;
    try {
        reader.next(r);
        ADD_FAILURE() << "a header-only metadata.csv read as an empty flight";
    } catch (const Error& e) {
        EXPECT_NE(std::string(e.what()).find("metadata.csv: no frame rows after the header"), std::string::npos) << e.what();
    }
    std::filesystem::remove_all(dir);
}

TEST(AirFormat, FlightInfoRefusesAbsurdCameraFpsAndResolution) {
    const std::string dir = temp_folder("bad_info");
    std::filesystem::create_directories(dir);
    const std::string path = dir + "/flight.json";
    auto error_for = [&](const std::string& json) {
        std::ofstream(path) << json;
        try {
            read_flight_info(path);
        } catch (const Error& e) {
            return std::string(e.what());
        }
        return std::string();
    };
    const std::string cam = R"("camera": {"width": 640, "height": 480, "hfov_deg": 60})";
    EXPECT_EQ(error_for(R"({"metres_per_pixel": 0.5, )" + cam + R"(, "fps": 50, "map_year": 2008})"), "");
    EXPECT_NE(error_for(R"({"metres_per_pixel": 0, )" + cam + "}").find(path + ": metres_per_pixel 0 must be a number in (0, 1000]"),
              std::string::npos);
    EXPECT_NE(error_for(R"({"metres_per_pixel": 1, )" + cam + R"(, "fps": 1e9})").find(path + ": fps 1000000000.0 must be"),
              std::string::npos);
    EXPECT_NE(error_for(R"({"metres_per_pixel": 1, "camera": {"width": 640.5, "height": 480, "hfov_deg": 60}})")
                  .find(path + ": camera.width 640.5 must be a whole number in [2, 16384]"),
              std::string::npos);
    EXPECT_NE(error_for(R"({"metres_per_pixel": 1, "camera": {"width": 640, "height": 480, "hfov_deg": 170}})")
                  .find(path + ": camera.hfov_deg 170 must be a number in (1, 170)"),
              std::string::npos);
    EXPECT_NE(error_for(R"({"metres_per_pixel": 1, "origin": {"latitude_deg": 100, "longitude_deg": 0}, )" + cam + "}")
                  .find(path + ": origin.latitude_deg 100 must be"),
              std::string::npos);
    EXPECT_NE(error_for(R"({"metres_per_pixel": 1, )" + cam + R"(, "map_year": 12})").find(path + ": map_year 12 must be 0 (unknown)"),
              std::string::npos);
    // Seed and frame count: never a float-to-integer cast (1e300 was undefined behaviour).
    EXPECT_EQ(error_for(R"({"metres_per_pixel": 1, )" + cam + R"(, "seed": 18446744073709551615, "frames": 16})"), "");
    EXPECT_NE(error_for(R"({"metres_per_pixel": 1, )" + cam + R"(, "seed": 1e300})").find(path + ": seed 1e+300 must be a whole number"),
              std::string::npos);
    EXPECT_NE(error_for(R"({"metres_per_pixel": 1, )" + cam + R"(, "seed": -1})").find(path + ": seed -1 must be a whole number"),
              std::string::npos);
    EXPECT_NE(error_for(R"({"metres_per_pixel": 1, )" + cam + R"(, "frames": 2.5})").find(path + ": frames 2.5 must be a whole number"),
              std::string::npos);
    std::filesystem::remove_all(dir);
}

// Random byte edits of a valid file: the parser must parse or throw trn::Error, nothing else,
// and never read out of bounds (run under sanitizers in the fuzz build).
TEST(AirFormat, FuzzedMetadataParsesOrThrowsTrnError) {
    const std::string valid =
        std::string(kHeader) + kRow + "\"q,\"\"x\"\".png\",1,2,3,0,0,0,1,0,0,0,0,0,0,1,5,6,7,8,9\n" + "b" + (kRow + 1);
    const std::string alphabet = ",\"\n\r .-e0123456789abcXYZ\t\xEF\xBB\xBF";
    std::uint64_t state = 12345;
    auto rnd = [&](std::uint64_t n) {
        state = state * 6364136223846793005ull + 1442695040888963407ull;
        return (state >> 33) % n;
    };
    int parsed = 0, rejected = 0;
    for (int iter = 0; iter < 3000; ++iter) {
        std::string s = valid;
        const int edits = 1 + static_cast<int>(rnd(6));
        for (int e = 0; e < edits; ++e) {
            const std::size_t pos = rnd(s.size() + 1);
            switch (rnd(3)) {
                case 0: s.insert(s.begin() + pos, alphabet[rnd(alphabet.size())]); break;
                case 1: if (pos < s.size()) s.erase(pos, 1 + rnd(4)); break;
                default: if (pos < s.size()) s[pos] = alphabet[rnd(alphabet.size())]; break;
            }
        }
        std::stringstream in(s);
        try {
            AirMetadataParser p(in, "fuzz.csv");
            AirRecord r;
            while (p.next(r)) {
                EXPECT_FALSE(r.filename.empty());
                EXPECT_TRUE(std::isfinite(r.map_x));
            }
            ++parsed;
        } catch (const Error& e) {
            EXPECT_NE(std::string(e.what()).find("fuzz.csv"), std::string::npos) << e.what();
            ++rejected;
        }
    }
    EXPECT_GT(parsed, 50);
    EXPECT_GT(rejected, 50);
}

}  // namespace
}  // namespace trn::sim
