// trn/io/geotiff.hpp with GDAL: the raster, its geotransform and CRS; lat/lon through PROJ.
#include <cmath>
#include <cstdio>
#include <mutex>
#include <opencv2/imgproc.hpp>

#include <cpl_error.h>
#include <gdal_priv.h>
#include <ogr_spatialref.h>

#include "trn/error.hpp"
#include "trn/io/geotiff.hpp"
#include "trn/io/input_file.hpp"
#include "trn/limits.hpp"

namespace trn::io {
namespace {

void register_drivers() {
    static std::once_flag once;
    std::call_once(once, [] { GDALAllRegister(); });
}

std::string last_gdal_error() {
    const char* m = CPLGetLastErrorMsg();
    return m && *m ? std::string(" (") + m + ")" : std::string();
}

std::string number(double v) {
    char buf[40];
    std::snprintf(buf, sizeof buf, "%.10g", v);
    return buf;
}

// A GDAL configuration option for this thread only, restored when done: the restrictions below
// are passed in code, never read from (or left in) the environment of an embedding program.
class ThreadOption {
public:
    ThreadOption(const char* key, const char* value) : key_(key) {
        const char* old = CPLGetThreadLocalConfigOption(key, nullptr);
        had_ = old != nullptr;
        if (had_) old_ = old;
        CPLSetThreadLocalConfigOption(key, value);
    }
    ~ThreadOption() { CPLSetThreadLocalConfigOption(key_, had_ ? old_.c_str() : nullptr); }
    ThreadOption(const ThreadOption&) = delete;
    ThreadOption& operator=(const ThreadOption&) = delete;

private:
    const char* key_;
    std::string old_;
    bool had_ = false;
};

// The raster drivers a map needs. Not VRT (an XML file naming other files, /etc/passwd or
// /vsicurl/ URLs, as its pixels), not the network or archive drivers, not any driver whose
// "file" is a connection string.
const char* const kAllowedDrivers[] = {"GTiff", "PNG", "JPEG", nullptr};

struct DatasetCloser {
    void operator()(GDALDataset* d) const { GDALClose(d); }
};
struct TransformDeleter {
    void operator()(OGRCoordinateTransformation* t) const { OGRCoordinateTransformation::DestroyCT(t); }
};

// Reads band `b` (1-based) as 8-bit.
void read_band(GDALDataset& ds, int b, cv::Mat& out, const std::string& path) {
    GDALRasterBand* band = ds.GetRasterBand(b);
    if (band->GetRasterDataType() != GDT_Byte)
        throw Error(path + ": band " + std::to_string(b) + " is " + GDALGetDataTypeName(band->GetRasterDataType()) +
                    "; only 8-bit orthophotos are supported (gdal_translate -ot Byte -scale)");
    out.create(ds.GetRasterYSize(), ds.GetRasterXSize(), CV_8UC1);
    CPLErrorReset();
    if (band->RasterIO(GF_Read, 0, 0, out.cols, out.rows, out.data, out.cols, out.rows, GDT_Byte, 0, 0) != CE_None)
        throw Error(path + ": cannot read band " + std::to_string(b) + last_gdal_error());
}

}  // namespace

bool geotiff_supported() { return true; }

GeoTiff read_geotiff(const std::string& path, std::optional<int> nodata) {
    if (nodata && (*nodata < 0 || *nodata > 255))
        throw Error(path + ": no-data value " + std::to_string(*nodata) + " is not an 8-bit grey level (0..255)");
    // A local regular file only: no /vsicurl/ or other virtual path, no "GTIFF_DIR:2:x.tif" or
    // other sub-dataset syntax (neither names a file), no FIFO or device.
    if (path.rfind("/vsi", 0) == 0) throw Error(path + ": GDAL virtual file systems (/vsi...) are not read; give a local file");
    check_input_file(path, kMaxImageFileBytes, "a map");
    register_drivers();
    // Only the file itself: no directory listing on open, so no sibling files (.aux.xml, .ovr,
    // .msk) are looked for or followed, and no .aux.xml metadata is read or written.
    const ThreadOption no_siblings("GDAL_DISABLE_READDIR_ON_OPEN", "EMPTY_DIR"), no_pam("GDAL_PAM_ENABLED", "NO");
    CPLErrorReset();
    std::unique_ptr<GDALDataset, DatasetCloser> ds(GDALDataset::FromHandle(
        GDALOpenEx(path.c_str(), GDAL_OF_RASTER | GDAL_OF_READONLY, const_cast<char**>(kAllowedDrivers), nullptr, nullptr)));
    if (!ds) throw Error(path + ": not a readable GeoTIFF (GTiff, PNG and JPEG files are read; not VRT or other indirections)" + last_gdal_error());

    GeoTiff g;
    const int width = ds->GetRasterXSize(), height = ds->GetRasterYSize(), bands = ds->GetRasterCount();
    limits::check_image(path + ": image", width, height, limits::kMaxMapPixels, limits::kLoadBytesPerPixel);
    if (bands != 1 && bands != 3 && bands != 4)
        throw Error(path + ": " + std::to_string(bands) + " bands; expected 1 (grey), 3 (RGB) or 4 (RGBA)");

    // Where the pixels are: north-up, square, in metres. A rotated geotransform would need the
    // filter to work in a rotated frame; better refused than silently mislocated.
    if (ds->GetGeoTransform(g.geotransform.data()) != CE_None)
        throw Error(path + ": no geotransform; the file is not georeferenced (give a PNG map and its metres per pixel instead)");
    const auto& gt = g.geotransform;
    if (gt[2] != 0 || gt[4] != 0)
        throw Error(path + ": the geotransform is rotated or sheared (row/column terms " + number(gt[2]) + ", " + number(gt[4]) +
                    "); only north-up maps are supported (gdalwarp it to north-up first)");
    if (!(gt[1] > 0) || !(gt[5] < 0))
        throw Error(path + ": the geotransform is not north-up (pixel width " + number(gt[1]) + ", height " + number(gt[5]) +
                    "; expected width > 0, height < 0)");
    if (std::fabs(gt[1] + gt[5]) > 1e-6 * gt[1])
        throw Error(path + ": pixels are not square (" + number(gt[1]) + " x " + number(-gt[5]) + "); resample to square pixels");

    const OGRSpatialReference* srs = ds->GetSpatialRef();
    if (!srs || srs->IsEmpty())
        throw Error(path + ": no coordinate reference system, CRS: cannot tell metres or latitude/longitude (assign one, e.g. "
                           "gdal_edit.py -a_srs EPSG:32632)");
    if (!srs->IsProjected())
        throw Error(path + ": CRS '" + std::string(srs->GetName() ? srs->GetName() : "?") +
                    "' is not a projected CRS in metres (a geographic one has pixels in degrees); reproject it, e.g. to UTM");
    g.metres_per_pixel = gt[1] * srs->GetLinearUnits();
    if (!(g.metres_per_pixel > 0 && g.metres_per_pixel <= 1000))
        throw Error(path + ": resolution " + number(g.metres_per_pixel) + " m/px is outside (0, 1000]");
    g.crs_name = srs->GetName() ? srs->GetName() : "";
    char* wkt = nullptr;
    srs->exportToWkt(&wkt);
    g.crs_wkt = wkt ? wkt : "";
    CPLFree(wkt);

    cv::Mat grey, rgb[3];
    if (bands == 1) {
        read_band(*ds, 1, grey, path);
        rgb[0] = grey;
    } else {
        cv::Mat merged;
        for (int b = 0; b < 3; ++b) read_band(*ds, b + 1, rgb[b], path);
        cv::merge(rgb, 3, merged);
        cv::cvtColor(merged, grey, cv::COLOR_RGB2GRAY);
    }
    g.image.width = width, g.image.height = height;
    g.image.pixels.assign(grey.datastart, grey.dataend);

    // No-data: GDAL's mask of band 1 (alpha band, nodata value or internal mask), then `nodata`.
    cv::Mat valid;
    GDALRasterBand* first = ds->GetRasterBand(1);
    if ((first->GetMaskFlags() & GMF_ALL_VALID) == 0) {
        valid.create(height, width, CV_8UC1);
        CPLErrorReset();
        if (first->GetMaskBand()->RasterIO(GF_Read, 0, 0, width, height, valid.data, width, height, GDT_Byte, 0, 0) != CE_None)
            throw Error(path + ": cannot read the no-data mask" + last_gdal_error());
        valid.setTo(255, valid != 0);
    }
    if (nodata) {
        cv::Mat same = rgb[0] == *nodata;
        for (int b = 1; b < 3 && bands > 1; ++b) same &= rgb[b] == *nodata;
        if (valid.empty()) valid = cv::Mat(height, width, CV_8UC1, cv::Scalar(255));
        valid.setTo(0, same);
    }
    if (!valid.empty()) {
        g.valid.width = width, g.valid.height = height;
        g.valid.pixels.assign(valid.datastart, valid.dataend);
    }
    return g;
}

struct GeoReference::Impl {
    std::array<double, 6> gt{};
    std::unique_ptr<OGRCoordinateTransformation, TransformDeleter> to_geo, from_geo;
    std::string source;
};

GeoReference::GeoReference(const GeoTiff& map, const std::string& source) : impl_(std::make_unique<Impl>()) {
    impl_->gt = map.geotransform;
    impl_->source = source;
    OGRSpatialReference crs, wgs84;
    if (crs.importFromWkt(map.crs_wkt.c_str()) != OGRERR_NONE) throw Error(source + ": CRS cannot be read back from its WKT");
    wgs84.SetWellKnownGeogCS("WGS84");
    // Longitude first, latitude second, whatever the CRS's official axis order.
    crs.SetAxisMappingStrategy(OAMS_TRADITIONAL_GIS_ORDER);
    wgs84.SetAxisMappingStrategy(OAMS_TRADITIONAL_GIS_ORDER);
    CPLErrorReset();
    impl_->to_geo.reset(OGRCreateCoordinateTransformation(&crs, &wgs84));
    impl_->from_geo.reset(OGRCreateCoordinateTransformation(&wgs84, &crs));
    if (!impl_->to_geo || !impl_->from_geo)
        throw Error(source + ": no transformation from its CRS '" + map.crs_name + "' to WGS84 latitude/longitude" + last_gdal_error());
}

GeoReference::~GeoReference() = default;
GeoReference::GeoReference(GeoReference&&) noexcept = default;
GeoReference& GeoReference::operator=(GeoReference&&) noexcept = default;

GeoPoint GeoReference::to_latlon(double x, double y) const {
    const auto& gt = impl_->gt;
    double e = gt[0] + (x + 0.5) * gt[1] + (y + 0.5) * gt[2], n = gt[3] + (x + 0.5) * gt[4] + (y + 0.5) * gt[5];
    if (!impl_->to_geo->Transform(1, &e, &n))
        throw Error(impl_->source + ": map pixel " + number(x) + "," + number(y) + " has no latitude/longitude");
    return {n, e};
}

std::array<double, 2> GeoReference::to_pixel(double latitude_deg, double longitude_deg) const {
    const auto& gt = impl_->gt;
    double e = longitude_deg, n = latitude_deg;
    if (!impl_->from_geo->Transform(1, &e, &n))
        throw Error(impl_->source + ": latitude/longitude " + number(latitude_deg) + "," + number(longitude_deg) + " cannot be projected");
    return {(e - gt[0]) / gt[1] - 0.5, (n - gt[3]) / gt[5] - 0.5};  // north-up: gt[2] = gt[4] = 0
}

}  // namespace trn::io
