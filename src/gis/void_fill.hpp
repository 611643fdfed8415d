#pragma once
// Private: filling the voids of a resampled DEM.
#include <cstdint>
#include <vector>

#include "avalanche/gis/geo_grid.hpp"

namespace avalanche::gis::detail {

struct VoidFillResult {
    int holes = 0;                     // void cells enclosed by data
    int outside = 0;                   // void cells connected to the grid border
    std::vector<std::uint8_t> origin;  // CellOrigin per cell
};

// Fills every non-finite cell of z (solver orientation) and classifies the filled cells.
// Within 64 cells of data: GDALFillNodata's inverse-distance interpolation from the
// nearest valid cells in four quadrants. Farther (large areas outside the footprint):
// the mean of the already-filled neighbours, ring by ring, which levels off. z must
// hold at least one finite value. The interpolation runs in bands of rows on up to
// `threads` threads; the values do not depend on their number.
VoidFillResult fill_voids(const GeoGrid& geo, std::vector<double>& z, int threads = 1);

}  // namespace avalanche::gis::detail
