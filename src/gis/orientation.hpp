#pragma once
// Orientation between GIS rasters (north-up, row 0 = northernmost row) and the
// solver (j = 0 = southernmost row). STYLE.md convention 10: the row flip lives in
// exactly one function, flipped_row; every read and write goes through
// read_solver_rows / write_solver_rows / mem_from_solver_rows, which use it (through
// flip_north_south for whole rasters).
#include <cstddef>
#include <cstdint>
#include <vector>

#include "avalanche/gis/geo_grid.hpp"
#include "gdal_support.hpp"

namespace avalanche::gis::detail {

// The GDAL (north-up) row that holds solver row `row`, and the solver row of GDAL row
// `row`: the one reversal, its own inverse.
inline int flipped_row(int row, int ny) { return ny - 1 - row; }

// Reverses the order of the ny rows of an nx-wide row-major raster. It is its own
// inverse: GeoTIFF rows -> solver rows, and solver rows -> GeoTIFF rows.
template <class T>
std::vector<T> flip_north_south(const std::vector<T>& rows, int nx, int ny) {
    std::vector<T> out(rows.size());
    const auto width = static_cast<std::size_t>(nx);
    for (int r = 0; r < ny; ++r) {
        const auto from = rows.begin() + static_cast<std::ptrdiff_t>(width * r);
        std::copy(from, from + static_cast<std::ptrdiff_t>(width),
                  out.begin() + static_cast<std::ptrdiff_t>(width * flipped_row(r, ny)));
    }
    return out;
}

// An empty north-up MEM raster on the cells of `geo` (geotransform and CRS set).
DatasetPtr mem_for_grid(const GeoGrid& geo, int bands, GDALDataType type);

// Band `band` of a north-up dataset covering exactly geo.grid, in solver orientation.
// Throws InputError(file) on read failure.
std::vector<double> read_solver_rows(GDALDataset& ds, int band, const Grid& grid,
                                     const std::string& file);

// Writes solver-oriented `values` into band `band` of a north-up dataset on geo.grid,
// a row at a time into its flipped row (no grid-sized flipped copy: on a large grid that
// copy's first-touched memory cost more than the write). T is double or std::uint8_t.
template <class T>
void write_solver_rows(GDALDataset& ds, int band, const Grid& grid, const std::vector<T>& values);

// A north-up MEM raster holding solver-oriented `values` in band 1.
DatasetPtr mem_from_solver_rows(const GeoGrid& geo, const std::vector<double>& values,
                                GDALDataType type);

}  // namespace avalanche::gis::detail
