#pragma once
// Private CRS helpers: spatial references always in traditional GIS axis order
// (x = easting/longitude first), so that EPSG:4326 or EPSG:31287, whose official
// axis order is northing first, never swap coordinates silently.
#include <ogr_spatialref.h>

#include <memory>
#include <string>

namespace avalanche::gis::detail {

struct TransformDeleter {
    void operator()(OGRCoordinateTransformation* t) const {
        OGRCoordinateTransformation::DestroyCT(t);
    }
};
using TransformPtr = std::unique_ptr<OGRCoordinateTransformation, TransformDeleter>;

// Spatial reference from WKT (or any user input), traditional axis order; empty
// reference (IsEmpty) for an empty string. Throws ConfigError(key) when unreadable.
OGRSpatialReference srs_from_text(const std::string& text, const std::string& key);
// Copy with traditional axis order set.
OGRSpatialReference traditional(const OGRSpatialReference& srs);
std::string to_wkt(const OGRSpatialReference& srs);
// EPSG code of a CRS (from its ID, or identified by PROJ at >= 90 % confidence), or 0.
int epsg_of(const OGRSpatialReference& srs);
// "NAME (EPSG:code)" or "NAME".
std::string label_of(const OGRSpatialReference& srs);
// The source -> target transformation; throws InputError(file) when PROJ has none.
TransformPtr make_transform(const OGRSpatialReference& from, const OGRSpatialReference& to,
                            const std::string& file);

}  // namespace avalanche::gis::detail
