#pragma once
// Digital elevation models: reading (mosaic, reprojection, resampling, void filling)
// onto the solver's metric grid, and writing the computational DEM back out.
// All rasters in memory are in SOLVER orientation: index j*nx + i, j = 0 = south.
#include <cstdint>
#include <string>
#include <vector>

#include "avalanche/gis/geo_grid.hpp"

namespace avalanche::gis {

struct DemOptions {
    // Target CRS. "" keeps the DEM's own projected CRS, or picks the UTM zone of the
    // DEM's centre for a geographic DEM (EPSG:4326, ASTER GDEM, SRTM). Otherwise a
    // projected metric CRS as EPSG:xxxx, WKT or PROJ string. A tile without a CRS is
    // taken to be in this CRS (and is refused when it is "").
    std::string crs;
    // Cell size (m). 0 = the DEM's own resolution; for a DEM in another CRS, its
    // pixel spacing converted to metres at the DEM centre (the coarser axis),
    // rounded to a multiple of half a power of ten (30.9 m -> 30 m).
    double cell_size = 0.0;
    // Multiplies the automatic cell size (cell_size = 0) only: `--quality draft|fine`
    // scales the DEM's own resolution (include/avalanche/app/quality_preset.hpp).
    double cell_size_factor = 1.0;
    // GDAL resampling: nearest, bilinear, cubic, cubicspline, lanczos, average.
    // Bilinear by default: no new extrema, no staircase slopes (see docs/gis.md).
    // When the grid equals the source grid nothing is resampled whatever this says.
    std::string resampling = "bilinear";
    // The grid is refused (InputError naming the DEM files, before the DEM is read)
    // if cells * solver_bytes_per_cell exceeds this (bytes). The command line sets it
    // to the available memory or AVALANCHE_MAX_MEMORY_GB (src/app/prepare_dem.cpp).
    double max_solver_bytes = 8.0 * 1024.0 * 1024.0 * 1024.0;
    double solver_bytes_per_cell = 200.0;  // estimate of the solver state per cell
    std::string memory_limit_source = "the default limit";  // named in the refusal
    // Threads of GDAL's warp kernel and of the void fill's interpolation (the run's
    // OpenMP threads from the command line); the cells are the same for any count.
    int threads = 1;
};

// Where an elevation comes from (Dem::filled_mask).
enum class CellOrigin : std::uint8_t {
    measured = 0,        // from the DEM (possibly resampled)
    filled_hole = 1,     // void enclosed by data, interpolated
    filled_outside = 2,  // void connected to the grid border (outside the DEM's
                         // footprint, e.g. reprojected corners), extrapolated
};

struct Dem {
    GeoGrid geo;
    std::vector<double> z;                  // elevation (m), solver orientation, every cell finite
    int filled_voids = 0;                   // cells not covered by valid DEM data, filled
    int filled_holes = 0;                   // of which enclosed holes
    int filled_outside = 0;                 // of which outside the data footprint
    std::vector<std::uint8_t> filled_mask;  // CellOrigin per cell, solver orientation
    double z_min = 0.0, z_max = 0.0;        // range of the measured cells (m)
    std::string description_of_steps;       // one paragraph for logs and reports
};

// Reads one or several DEM tiles (any GDAL raster, each with its own CRS) and warps
// them onto one metric grid. Voids (nodata, NaN, Inf) are filled by inverse-distance
// interpolation (GDALFillNodata) and counted. Throws InputError for unreadable,
// corrupt, CRS-less (unless opts.crs) or all-nodata files and for grids above the
// memory limit (checked before any cell is read), ConfigError for bad options.
Dem load_dem(const std::vector<std::string>& paths, const DemOptions& opts = {});

// Writes the computational DEM as a COG GeoTIFF (Float32, nodata -9999 never used
// since every cell is filled), with the void counts in the band metadata.
void write_dem(const std::string& path, const Dem& dem);

}  // namespace avalanche::gis
