// GeoTIFF orthophotos (issue 12 item 4): GeoTIFFs are written here with GDAL (UTM zone 32N,
// 0.5 m pixels), read back by trn::io, and the real flight is localized on one with its estimates
// also as latitude / longitude. In a build without GDAL every test here is reported as skipped
// (NOT AVAILABLE), and a .tif map is refused by name.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <memory>
#include <optional>
#include <sstream>

#include "real_air_fixture.hpp"
#include "trn/error.hpp"
#include "trn/io/geotiff.hpp"
#include "trn/io/image_io.hpp"

#ifdef TRN_HAVE_GDAL
#include <gdal_priv.h>
#include <ogr_spatialref.h>
#include "trn/detail/angles.hpp"
#endif

using trn::test::RealAirFolder;
using trn::test::run_trnkit;

namespace {

using trn::kPi;

// UTM zone 32N on its central meridian (9 E): easting 500000 m is longitude 9 exactly and the
// northing is k0 * (meridian arc), so 0.9996 * 4984944.378 m (WGS84 arc to 45 N) = 4982950.400 m
// is latitude 45 exactly. Map pixel (100, 200) is put there.
constexpr double kPixelX = 100, kPixelY = 200, kEasting = 500000, kNorthing = 4982950.400;
constexpr double kMpp = 0.5;

#ifdef TRN_HAVE_GDAL
enum class Georef { utm32n, rotated, no_crs };

void write_geotiff(const std::string& path, const trn::GrayImage& image, Georef how, std::optional<int> nodata = std::nullopt) {
    GDALAllRegister();
    GDALDriver* driver = GetGDALDriverManager()->GetDriverByName("GTiff");
    ASSERT_NE(driver, nullptr);
    GDALDataset* ds = driver->Create(path.c_str(), image.width, image.height, 1, GDT_Byte, nullptr);
    ASSERT_NE(ds, nullptr);
    // Pixel centre (x, y) is GDAL pixel/line (x + 0.5, y + 0.5).
    double gt[6] = {kEasting - (kPixelX + 0.5) * kMpp, kMpp, 0, kNorthing + (kPixelY + 0.5) * kMpp, 0, -kMpp};
    if (how == Georef::rotated) gt[2] = 0.05, gt[4] = 0.05;
    ds->SetGeoTransform(gt);
    if (how != Georef::no_crs) {
        OGRSpatialReference srs;
        ASSERT_EQ(srs.importFromEPSG(32632), OGRERR_NONE);
        ds->SetSpatialRef(&srs);
    }
    if (nodata) ASSERT_EQ(ds->GetRasterBand(1)->SetNoDataValue(*nodata), CE_None);
    ASSERT_EQ(ds->GetRasterBand(1)->RasterIO(GF_Write, 0, 0, image.width, image.height, const_cast<std::uint8_t*>(image.pixels.data()),
                                             image.width, image.height, GDT_Byte, 0, 0),
              CE_None);
    GDALClose(ds);
}

trn::GrayImage texture(int w, int h) {
    trn::GrayImage g{w, h, std::vector<std::uint8_t>(std::size_t(w) * h)};
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) g.pixels[std::size_t(y) * w + x] = static_cast<std::uint8_t>((x * 7 + y * 13) % 251);
    return g;
}
#endif

#define SKIP_WITHOUT_GDAL()                                                                            \
    do {                                                                                               \
        if (!trn::io::geotiff_supported()) GTEST_SKIP() << "GDAL NOT AVAILABLE: GeoTIFF maps not built"; \
    } while (0)

std::string temp(const std::string& name) { return testing::TempDir() + "/geotiff_" + std::to_string(::getpid()) + "_" + name; }

}  // namespace

TEST(GeoTiffMap, ResolutionAndLatLonOfAKnownPixelMatchTheHandComputedUtmValues) {
    SKIP_WITHOUT_GDAL();
#ifdef TRN_HAVE_GDAL
    const std::string path = temp("utm.tif");
    write_geotiff(path, texture(300, 260), Georef::utm32n);
    const trn::io::GeoTiff g = trn::io::read_geotiff(path);
    EXPECT_EQ(g.image.width, 300);
    EXPECT_EQ(g.image.pixels, texture(300, 260).pixels);
    EXPECT_DOUBLE_EQ(g.metres_per_pixel, 0.5);
    EXPECT_EQ(g.crs_name, "WGS 84 / UTM zone 32N");
    const trn::io::GeoReference geo(g, path);
    const trn::io::GeoPoint p = geo.to_latlon(kPixelX, kPixelY);
    EXPECT_NEAR(p.latitude_deg, 45.0, 1e-8);  // 1e-8 deg is ~1 mm
    EXPECT_NEAR(p.longitude_deg, 9.0, 1e-8);
    // 200 px (100 m) east at 45 N: 100 m / (cos 45 * 111.3 km/deg) ~ 0.00127 deg of longitude.
    const trn::io::GeoPoint e = geo.to_latlon(kPixelX + 200, kPixelY);
    EXPECT_NEAR(e.longitude_deg - 9.0, 100 / (std::cos(45 * kPi / 180) * 111319.49), 2e-6);
    const auto back = geo.to_pixel(p.latitude_deg, p.longitude_deg);  // the inverse, to 1 um
    EXPECT_NEAR(back[0], kPixelX, 2e-6);
    EXPECT_NEAR(back[1], kPixelY, 2e-6);
    const auto hand = geo.to_pixel(45.0, 9.0);  // the hand value's northing is rounded to 1 mm
    EXPECT_NEAR(hand[0], kPixelX, 1e-3);
    EXPECT_NEAR(hand[1], kPixelY, 1e-3);
    std::filesystem::remove(path);
#endif
}

TEST(GeoTiffMap, RefusesRotatedAndCrsLessFilesNamingThem) {
    SKIP_WITHOUT_GDAL();
#ifdef TRN_HAVE_GDAL
    const std::string rotated = temp("rotated.tif"), no_crs = temp("no_crs.tif");
    write_geotiff(rotated, texture(64, 64), Georef::rotated);
    write_geotiff(no_crs, texture(64, 64), Georef::no_crs);
    for (const auto& [path, why] : {std::pair{rotated, "geotransform is rotated or sheared"}, std::pair{no_crs, "no coordinate reference system"}}) {
        try {
            trn::io::read_geotiff(path);
            ADD_FAILURE() << path << " was accepted";
        } catch (const trn::Error& e) {
            EXPECT_EQ(std::string(e.what()).rfind(path + ": ", 0), 0u) << e.what();
            EXPECT_NE(std::string(e.what()).find(why), std::string::npos) << e.what();
        }
        // The CLI: one line, exit 1, before any work.
        const auto r = run_trnkit("localize --dataset " + testing::TempDir() + " --map " + path + " --hfov-deg 60 --no-plots --out " +
                                  temp("never"));
        EXPECT_EQ(r.code, 1) << r.output;
        EXPECT_NE(r.output.find(why), std::string::npos) << r.output;
        EXPECT_FALSE(std::filesystem::exists(temp("never")));
        std::filesystem::remove(path);
    }
#endif
}

// A map whose extent crosses the antimeridian (issue 45 class 6): a UTM zone 60S map over Fiji
// whose pixel column 100 lies on 180 deg. Its latitude/longitude come back wrapped into [-180, 180]
// (PROJ normalises them), fixes 2 m apart across the antimeridian map to pixels 2 m apart (not
// 40 075 km), and every pixel round-trips. The same extent in a geographic CRS (pixels in degrees,
// where the wrap would fall inside the raster) is refused naming the file and what to do.
TEST(GeoTiffMap, AMapAcrossTheAntimeridianHasWrappedLongitudesAndShortDistances) {
    SKIP_WITHOUT_GDAL();
#ifdef TRN_HAVE_GDAL
    GDALAllRegister();
    OGRSpatialReference utm, wgs84;
    ASSERT_EQ(utm.importFromEPSG(32760), OGRERR_NONE);
    ASSERT_EQ(wgs84.importFromEPSG(4326), OGRERR_NONE);
    utm.SetAxisMappingStrategy(OAMS_TRADITIONAL_GIS_ORDER);
    wgs84.SetAxisMappingStrategy(OAMS_TRADITIONAL_GIS_ORDER);
    std::unique_ptr<OGRCoordinateTransformation> to_utm(OGRCreateCoordinateTransformation(&wgs84, &utm));
    ASSERT_NE(to_utm, nullptr);
    double e180 = 180.0, n180 = -17.0;  // the antimeridian at 17 S, in zone 60S metres
    ASSERT_TRUE(to_utm->Transform(1, &e180, &n180));
    auto write = [&](const std::string& path, const OGRSpatialReference& crs, const double (&gt)[6]) {
        GDALDataset* ds = GetGDALDriverManager()->GetDriverByName("GTiff")->Create(path.c_str(), 200, 100, 1, GDT_Byte, nullptr);
        ASSERT_NE(ds, nullptr);
        ds->SetGeoTransform(const_cast<double*>(gt));
        ds->SetSpatialRef(&crs);
        const trn::GrayImage t = texture(200, 100);
        ASSERT_EQ(ds->GetRasterBand(1)->RasterIO(GF_Write, 0, 0, 200, 100, const_cast<std::uint8_t*>(t.pixels.data()), 200, 100, GDT_Byte, 0, 0),
                  CE_None);
        GDALClose(ds);
    };
    const std::string path = temp("antimeridian.tif");
    const double gt[6] = {e180 - 100.5, 1.0, 0, n180 + 50.5, 0, -1.0};  // pixel centre (100, 50) on 180 deg, 17 S
    write(path, utm, gt);
    const trn::io::GeoTiff g = trn::io::read_geotiff(path);
    const trn::io::GeoReference geo(g, path);
    const trn::io::GeoPoint west = geo.to_latlon(99, 50), east = geo.to_latlon(101, 50), centre = geo.to_latlon(100, 50);
    EXPECT_NEAR(centre.latitude_deg, -17.0, 1e-8);
    EXPECT_NEAR(std::fabs(centre.longitude_deg), 180.0, 1e-8);
    EXPECT_GT(west.longitude_deg, 179.99);
    EXPECT_LE(west.longitude_deg, 180.0);
    EXPECT_GE(east.longitude_deg, -180.0);
    EXPECT_LT(east.longitude_deg, -179.99);
    const auto pw = geo.to_pixel(west.latitude_deg, west.longitude_deg), pe = geo.to_pixel(east.latitude_deg, east.longitude_deg);
    EXPECT_NEAR(pw[0], 99, 1e-6);
    EXPECT_NEAR(pe[0], 101, 1e-6);
    EXPECT_NEAR(std::hypot(pe[0] - pw[0], pe[1] - pw[1]) * g.metres_per_pixel, 2.0, 1e-5);  // 2 m, not 40 075 km
    const auto over = geo.to_pixel(-17.0, 180.00001 - 360);  // a fix written as -179.99999 or as 180.00001 is the same place
    const auto same = geo.to_pixel(-17.0, 180.00001);
    EXPECT_NEAR(over[0], same[0], 1e-6);
    EXPECT_NEAR(over[1], same[1], 1e-6);
    std::filesystem::remove(path);

    const std::string degrees = temp("antimeridian_degrees.tif");  // 179.9 .. 180.1 E in a geographic CRS
    const double gd[6] = {179.9, 0.001, 0, -16.95, 0, -0.001};
    write(degrees, wgs84, gd);
    try {
        trn::io::read_geotiff(degrees);
        ADD_FAILURE() << degrees << " was accepted";
    } catch (const trn::Error& e) {
        EXPECT_EQ(std::string(e.what()).rfind(degrees + ": CRS 'WGS 84' is not a projected CRS in metres", 0), 0u) << e.what();
        EXPECT_NE(std::string(e.what()).find("reproject it, e.g. to UTM"), std::string::npos) << e.what();
    }
    std::filesystem::remove(degrees);
#endif
}

// Without GDAL a .tif map is an error that says so (this build has GDAL, then this is skipped).
// Issue 23 finding 7: a "map" that is a VRT (XML naming other files as its pixels) read any file,
// here a secret outside the dataset, or could connect to a port (/vsicurl/). Only GTiff, PNG and
// JPEG are opened now, only local regular files, no GDAL virtual paths.
TEST(GeoTiffMap, VrtAndVirtualPathsAreNotOpened) {
    SKIP_WITHOUT_GDAL();
    const std::string secret = temp("secret.raw"), vrt = temp("evil.tif");
    std::ofstream(secret, std::ios::binary) << std::string(64 * 64, 'S');
    std::ofstream(vrt) << R"(<VRTDataset rasterXSize="64" rasterYSize="64">
  <SRS>EPSG:32632</SRS>
  <GeoTransform>500000, 0.5, 0, 4982950, 0, -0.5</GeoTransform>
  <VRTRasterBand dataType="Byte" band="1" subClass="VRTRawRasterBand">
    <SourceFilename relativetoVRT="0">)" << secret << R"(</SourceFilename>
    <ImageOffset>0</ImageOffset><PixelOffset>1</PixelOffset><LineOffset>64</LineOffset>
  </VRTRasterBand>
</VRTDataset>
)";
    for (const std::string& path : {vrt, std::string("/vsicurl/http://127.0.0.1:9/map.tif"), "GTIFF_DIR:1:" + vrt}) {
        try {
            const trn::io::GeoTiff g = trn::io::read_geotiff(path);
            ADD_FAILURE() << path << " was read (" << g.image.width << "x" << g.image.height << ", first byte " << int(g.image.pixels[0]) << ")";
        } catch (const trn::Error& e) {
            EXPECT_EQ(std::string(e.what()).find(path), 0u) << e.what();
        }
    }
}

// Issue 45, class 8: score and register read a GeoTIFF's no-data as localize does (its nodata
// value, alpha or mask band); they read it through OpenCV, which ignores all three.
TEST(GeoTiffMap, ScoreHonoursTheNodataValueAsLocalizeDoes) {
    SKIP_WITHOUT_GDAL();
#ifdef TRN_HAVE_GDAL
    trn::GrayImage img = texture(200, 150);
    for (int y = 0; y < 150; ++y)
        for (int x = 0; x < 200; ++x) {
            std::uint8_t& p = img.pixels[std::size_t(y) * 200 + x];
            p = x < 100 ? 0 : std::max<std::uint8_t>(p, 1);  // the west half the nodata value, the east half never
        }
    const std::string map = temp("nodata.tif"), templ = temp("nodata_templ.png"), poses = temp("nodata_poses.csv"), out = temp("nodata_out.csv");
    write_geotiff(map, img, Georef::utm32n, 0);
    trn::GrayImage t{32, 24, std::vector<std::uint8_t>(32 * 24)};
    for (int y = 0; y < 24; ++y)
        for (int x = 0; x < 32; ++x) t.pixels[std::size_t(y) * 32 + x] = img.pixels[std::size_t(y + 60) * 200 + x + 140];
    trn::save_gray(templ, t.view());
    std::ofstream(poses) << "x,y,yaw,scale\n155.5,71.5,0,1\n50,75,0,1\n";
    const auto r = run_trnkit("score --map " + map + " --template " + templ + " --poses " + poses + " --backend cpu -o " + out);
    ASSERT_EQ(r.code, 0) << r.output;
    std::ifstream in(out);
    std::string header, on_data, on_nodata;
    std::getline(in, header), std::getline(in, on_data), std::getline(in, on_nodata);
    auto valid_samples = [](const std::string& row) {
        std::vector<std::string> cells;
        std::stringstream ss(row);
        for (std::string c; std::getline(ss, c, ',');) cells.push_back(c);
        return cells.size() > 8 ? std::stol(cells[8]) : -1L;
    };
    EXPECT_EQ(valid_samples(on_data), 32 * 24) << on_data;
    EXPECT_EQ(valid_samples(on_nodata), 0) << on_nodata;  // every sample on the nodata value: left out
    for (const auto& f : {map, templ, poses, out}) std::remove(f.c_str());
#endif
}

TEST(GeoTiffMap, WithoutGdalATifMapIsRefusedNamingTheFile) {
    if (trn::io::geotiff_supported()) GTEST_SKIP() << "this build has GDAL; the refusal applies to builds without it";
    const auto r = run_trnkit("localize --dataset " + testing::TempDir() + " --map " + temp("x.tif") + " --hfov-deg 60 --no-plots");
    EXPECT_EQ(r.code, 1) << r.output;
    EXPECT_NE(r.output.find("GeoTIFF maps are read with GDAL, and this build of trnkit has none"), std::string::npos) << r.output;
}

// The real flight on the orthophoto as a GeoTIFF, no flight.json, no --mpp: the resolution comes
// from the geotransform, and every estimate is also written as latitude / longitude.
TEST_F(RealAirFolder, LocalizesOnAGeoTiffMapAndWritesLatLon) {
    SKIP_WITHOUT_GDAL();
#ifdef TRN_HAVE_GDAL
    const std::string tif = dir_ + "/orthophoto.tif";
    write_geotiff(tif, trn::load_gray(map()), Georef::utm32n);
    std::filesystem::remove(dir_ + "/flight.json");
    const std::string out = dir_ + "/geo";
    const auto r = localize("--map " + tif + " --hfov-deg 60", 1, out);
    ASSERT_EQ(r.code, 0) << r.output;
    const auto j = summary(out);
    std::cout << "GeoTIFF map: filter mean " << j["filter_mean_error_m"] << " m, odometry mean " << j["odometry_mean_error_m"] << " m, final "
              << j["final_estimate_lat"] << ", " << j["final_estimate_lon"] << "\n";
    EXPECT_EQ(j["metres_per_pixel"], 0.5);
    EXPECT_LE(j["filter_mean_error_m"].get<double>(), 0.5 * j["odometry_mean_error_m"].get<double>());
    EXPECT_NE(j["georeference"].get<std::string>().find("UTM zone 32N"), std::string::npos) << j.dump();
    const trn::io::GeoTiff g = trn::io::read_geotiff(tif);
    const trn::io::GeoReference geo(g, tif);
    const auto rows = csv(out + "/localization.csv");
    ASSERT_EQ(rows.size(), 16u);
    for (const auto& row : rows) {
        const trn::io::GeoPoint p = geo.to_latlon(std::stod(row.at("estimate_x")), std::stod(row.at("estimate_y")));
        EXPECT_NEAR(std::stod(row.at("est_lat")), p.latitude_deg, 1e-8);
        EXPECT_NEAR(std::stod(row.at("est_lon")), p.longitude_deg, 1e-8);
        EXPECT_NEAR(p.latitude_deg, 45, 0.01);  // the map spans ~0.9 km around 45 N, 9 E
        EXPECT_NEAR(p.longitude_deg, 9, 0.02);
    }
    EXPECT_NEAR(j["final_estimate_lat"].get<double>(), std::stod(rows.back().at("est_lat")), 1e-9);
    EXPECT_NEAR(j["final_estimate_lon"].get<double>(), std::stod(rows.back().at("est_lon")), 1e-9);
    // --mpp that contradicts the geotransform is refused.
    const auto bad = localize("--map " + tif + " --hfov-deg 60 --mpp 0.6", 1, dir_ + "/bad");
    EXPECT_EQ(bad.code, 1) << bad.output;
    EXPECT_NE(bad.output.find("--mpp: 0.6 contradicts " + tif), std::string::npos) << bad.output;
#endif
}
