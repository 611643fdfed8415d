#pragma once
// Writing solver rasters as Cloud-Optimized GeoTIFFs that open in QGIS and gdalinfo
// with their CRS, nodata, units and band description.
#include <map>
#include <string>
#include <vector>

#include "avalanche/gis/geo_grid.hpp"

namespace avalanche::gis {

// Sample type of the file (GDAL-free spelling of GDALDataType).
enum class SampleType { float32, float64, int16, int32, uint8, uint16 };

struct BandInfo {
    std::string description;  // e.g. "maximum flow depth (bed-normal)"
    std::string units;        // e.g. "m", "m/s", "kPa", "s" (GDALRasterBand::SetUnitType)
    double nodata = -9999.0;  // cells equal to this are nodata; must fit the sample type
    std::map<std::string, std::string> metadata;  // band metadata (thickness kind, config hash)
    // Dataset-level metadata (gdalinfo "Metadata:"), e.g. AVALANCHE_COMPLETE=YES|NO.
    std::map<std::string, std::string> dataset_metadata;
};

// DEFLATE's predictor (TIFF tag Predictor): `automatic` is GDAL's PREDICTOR=YES, the
// floating-point predictor for floats and horizontal differencing for integers. It
// pays on rasters of values everywhere (a DEM: half the size); on a hazard map, nodata
// outside the affected area, `none` gave smaller files in less time.
enum class Predictor { automatic, none };

// Writes `values` (solver orientation: index j*nx + i, j = 0 = south) as a COG:
// DEFLATE with `predictor`, internal tiles, overviews (average for float types, nearest
// for integer ones such as class maps), CRS and north-up geotransform from `geo`.
// The file appears atomically: it is written to "<path>.part" and renamed.
// Throws OutputError naming the file (and the first bad cell) for non-finite values,
// values that do not fit an integer type, or a failed write; no file is left behind.
void write_geotiff(const std::string& path, const GeoGrid& geo, const std::vector<double>& values,
                   const BandInfo& band, SampleType type = SampleType::float32,
                   Predictor predictor = Predictor::automatic);

}  // namespace avalanche::gis
