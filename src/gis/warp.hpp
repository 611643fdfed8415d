#pragma once
// Private: resampling GDAL datasets onto an exact solver grid.
#include <string>
#include <vector>

#include "avalanche/gis/geo_grid.hpp"
#include "gdal_support.hpp"

namespace avalanche::gis::detail {

// Checks a resampling name against GDAL's (nearest, bilinear, cubic, cubicspline,
// lanczos, average, ...) and returns GDAL's spelling; ConfigError(key) otherwise.
std::string gdal_resampling(const std::string& name, const std::string& key);

// Warps the sources (each with its own CRS and nodata; NaN is never used as data)
// onto the cells of `geo`: a north-up MEM Float64 raster whose uncovered cells are
// NaN. `label` names the input(s) in an InputError. `threads` share the warp kernel's
// rows (GDAL's NUM_THREADS): each destination row is computed whole by one thread, so
// the cells are the same whatever the count.
DatasetPtr warp_onto_grid(const std::vector<GDALDataset*>& sources, const GeoGrid& geo,
                          const std::string& resampling, const std::string& label,
                          GdalErrorScope& errors, int threads = 1);

}  // namespace avalanche::gis::detail
