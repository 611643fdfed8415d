#include "orientation.hpp"

#include <algorithm>
#include <type_traits>

#include "avalanche/core/error.hpp"

namespace avalanche::gis::detail {

DatasetPtr mem_for_grid(const GeoGrid& geo, int bands, GDALDataType type) {
    DatasetPtr ds = create_mem_raster(geo.grid.nx, geo.grid.ny, bands, type);
    auto gt = geo.geotransform();
    ds->SetGeoTransform(gt.data());
    if (!geo.crs_wkt.empty()) {
        OGRSpatialReference srs;
        srs.SetAxisMappingStrategy(OAMS_TRADITIONAL_GIS_ORDER);
        srs.importFromWkt(geo.crs_wkt.c_str());
        ds->SetSpatialRef(&srs);
    }
    return ds;
}

std::vector<double> read_solver_rows(GDALDataset& ds, int band, const Grid& grid,
                                     const std::string& file) {
    std::vector<double> rows(grid.cells());
    GDALRasterBand* b = ds.GetRasterBand(band);
    if (b == nullptr || ds.GetRasterXSize() != grid.nx || ds.GetRasterYSize() != grid.ny)
        throw Error(ExitCode::internal, file + ": raster does not match the grid");
    if (b->RasterIO(GF_Read, 0, 0, grid.nx, grid.ny, rows.data(), grid.nx, grid.ny, GDT_Float64, 0,
                    0, nullptr) != CE_None)
        throw InputError(file, "cannot read the raster values");
    return flip_north_south(rows, grid.nx, grid.ny);
}

namespace {
template <class T>
constexpr GDALDataType gdal_type_of() {
    if constexpr (std::is_same_v<T, double>)
        return GDT_Float64;
    else
        return GDT_Byte;
}
}  // namespace

template <class T>
void write_solver_rows(GDALDataset& ds, int band, const Grid& grid, const std::vector<T>& values) {
    static_assert(std::is_same_v<T, double> || std::is_same_v<T, std::uint8_t>);
    if (values.size() != grid.cells() || ds.GetRasterXSize() != grid.nx ||
        ds.GetRasterYSize() != grid.ny || ds.GetRasterBand(band) == nullptr)
        throw Error(ExitCode::internal, "raster values do not match the grid size");
    GDALRasterBand* b = ds.GetRasterBand(band);
    for (int j = 0; j < grid.ny; ++j) {
        T* row = const_cast<T*>(values.data()) + static_cast<std::size_t>(j) * grid.nx;
        if (b->RasterIO(GF_Write, 0, flipped_row(j, grid.ny), grid.nx, 1, row, grid.nx, 1,
                        gdal_type_of<T>(), 0, 0, nullptr) != CE_None)
            throw Error(ExitCode::internal, "cannot fill an in-memory raster");
    }
}
template void write_solver_rows(GDALDataset&, int, const Grid&, const std::vector<double>&);
template void write_solver_rows(GDALDataset&, int, const Grid&, const std::vector<std::uint8_t>&);

DatasetPtr mem_from_solver_rows(const GeoGrid& geo, const std::vector<double>& values,
                                GDALDataType type) {
    DatasetPtr ds = mem_for_grid(geo, 1, type);
    write_solver_rows(*ds, 1, geo.grid, values);
    return ds;
}

}  // namespace avalanche::gis::detail
