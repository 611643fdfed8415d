// CRS handling: UTM zone choice, user CRS parsing, labels.
#include <cmath>
#include <cstdlib>

#include "avalanche/core/error.hpp"
#include "avalanche/gis/geo_grid.hpp"
#include "crs_support.hpp"
#include "gdal_support.hpp"

namespace avalanche::gis {

namespace detail {

namespace {
constexpr int kEpsgMatchConfidence = 90;  // percent, PROJ's identification score
}  // namespace

OGRSpatialReference traditional(const OGRSpatialReference& srs) {
    OGRSpatialReference copy(srs);
    copy.SetAxisMappingStrategy(OAMS_TRADITIONAL_GIS_ORDER);
    return copy;
}

OGRSpatialReference srs_from_text(const std::string& text, const std::string& key) {
    ensure_gdal_registered();
    OGRSpatialReference srs;
    srs.SetAxisMappingStrategy(OAMS_TRADITIONAL_GIS_ORDER);
    if (text.empty()) return srs;
    GdalErrorScope errors;  // keep PROJ's complaints out of stderr
    if (srs.SetFromUserInput(text.c_str()) != OGRERR_NONE) {
        throw ConfigError(key, "cannot interpret '" + text +
                                   "' as a coordinate reference system (expected e.g. "
                                   "EPSG:31287, a WKT string or a PROJ string)" +
                                   errors.reason());
    }
    srs.SetAxisMappingStrategy(OAMS_TRADITIONAL_GIS_ORDER);
    return srs;
}

std::string to_wkt(const OGRSpatialReference& srs) {
    char* wkt = nullptr;
    const char* options[] = {"FORMAT=WKT2_2019", nullptr};
    srs.exportToWkt(&wkt, options);
    std::string out = wkt != nullptr ? wkt : "";
    CPLFree(wkt);
    return out;
}

int epsg_of(const OGRSpatialReference& srs) {
    if (srs.IsEmpty()) return 0;
    OGRSpatialReference copy(srs);
    if (copy.GetAuthorityCode(nullptr) == nullptr && copy.AutoIdentifyEPSG() != OGRERR_NONE) {
        // WKT without an ID (e.g. the avaKot DEM's "MGI / Austria Lambert"): ask PROJ for
        // an equivalent EPSG entry, accepted only at high confidence.
        GdalErrorScope quiet;
        OGRSpatialReference* match = copy.FindBestMatch(kEpsgMatchConfidence, "EPSG");
        if (match == nullptr) return 0;
        copy = *match;
        match->Release();
    }
    const char* authority = copy.GetAuthorityName(nullptr);
    const char* code = copy.GetAuthorityCode(nullptr);
    if (authority == nullptr || code == nullptr || std::string(authority) != "EPSG") return 0;
    return std::atoi(code);
}

std::string label_of(const OGRSpatialReference& srs) {
    if (srs.IsEmpty()) return "no CRS";
    const char* name = srs.GetName();
    std::string label = name != nullptr ? name : "unnamed CRS";
    if (const int code = epsg_of(srs)) label += " (EPSG:" + std::to_string(code) + ")";
    return label;
}

TransformPtr make_transform(const OGRSpatialReference& from, const OGRSpatialReference& to,
                            const std::string& file) {
    const OGRSpatialReference a = traditional(from);
    const OGRSpatialReference b = traditional(to);
    TransformPtr t(OGRCreateCoordinateTransformation(&a, &b));
    if (!t) {
        throw InputError(file,
                         "no coordinate transformation from " + label_of(a) + " to " + label_of(b));
    }
    return t;
}

}  // namespace detail

std::array<double, 6> GeoGrid::geotransform() const {
    return {grid.x0, grid.dx, 0.0, grid.y0 + grid.ny * grid.dy, 0.0, -grid.dy};
}

int GeoGrid::epsg() const { return detail::epsg_of(detail::srs_from_text(crs_wkt, "crs")); }

std::string GeoGrid::crs_label() const {
    return detail::label_of(detail::srs_from_text(crs_wkt, "crs"));
}

int utm_epsg_for(double lon, double lat) {
    if (!std::isfinite(lon) || !std::isfinite(lat) || lat > 84.0 || lat < -80.0) {
        throw ConfigError("crs", "no UTM zone at latitude " + std::to_string(lat) +
                                     " (UTM covers 80 S to 84 N); give a projected CRS");
    }
    // Wrap the longitude into [-180, 180) so that 180 E falls in zone 1.
    const double wrapped = lon - 360.0 * std::floor((lon + 180.0) / 360.0);
    int zone = static_cast<int>(std::floor((wrapped + 180.0) / 6.0)) + 1;
    if (zone > 60) zone = 60;
    return (lat >= 0.0 ? 32600 : 32700) + zone;
}

std::string utm_crs_wkt_for(double lon, double lat) {
    detail::ensure_gdal_registered();
    OGRSpatialReference srs;
    const int code = utm_epsg_for(lon, lat);
    if (srs.importFromEPSG(code) != OGRERR_NONE)
        throw ConfigError("crs", "PROJ database has no EPSG:" + std::to_string(code));
    return detail::to_wkt(srs);
}

std::string crs_wkt_from_user(const std::string& text, const std::string& key) {
    if (text.empty()) throw ConfigError(key, "empty coordinate reference system");
    return detail::to_wkt(detail::srs_from_text(text, key));
}

}  // namespace avalanche::gis
