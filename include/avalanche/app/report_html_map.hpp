#pragma once
// One map of report.html: the quick-look PNG (the same picture as <map>.png, embedded as a
// data: URI) with an inline-SVG overlay of the release outline, the monitoring points, a
// scale bar and a north arrow, and a legend of the map's colour ramp beside it.
#include <cstdint>
#include <string>
#include <vector>

#include "avalanche/core/grid.hpp"
#include "avalanche/gis/style.hpp"
#include "avalanche/output/monitoring.hpp"

namespace avalanche {

// The scale bar's length: the value 1, 2 or 5 x 10^n m nearest (by ratio) to a fifth of
// the map width. 0 for a width that is not positive and finite.
double scale_bar_length_m(double map_width_m);

// Display size of a map in CSS pixels: the grid scaled uniformly (in metres, so dx != dy
// keeps its aspect) to fit max_width x max_height.
struct MapDisplay {
    double width = 0, height = 0;  // px
    double px_per_m = 0;           // the same along both axes
};
MapDisplay map_display(const Grid& grid, double max_width, double max_height);

// The boundary between cells with mask != 0 and the others (or the grid edge) as SVG path
// data in display pixels, row 0 at the top (north): one "Mx yhL" / "Mx yvL" segment per cell
// edge. `mask` is in solver orientation (index j * nx + i, j = 0 south). "" for no cell.
std::string outline_path(const std::vector<std::uint8_t>& mask, const Grid& grid, double px_per_m);

struct MapOverlay {
    Grid grid;
    // Empty in the chute frame: no geographic north, lengths along the chute bed.
    std::string crs_label;
    std::vector<std::uint8_t> release;  // release cells (solver orientation); may be empty
    std::vector<ProbeLocation> points;  // monitoring points; may be empty
    // Whether the quick-looks hatch cells outside the DEM's data (gis::QuicklookShade).
    bool no_terrain_data = false;
};

struct MapFigure {
    std::string id;            // HTML id and the base name of the PNG, e.g. "max_depth"
    std::string title;         // e.g. "Maximum flow depth"
    std::string caption;       // plain words: what the colours mean
    std::string png;           // the PNG file's bytes; "" when it could not be read
    gis::ColorRamp ramp;       // the ramp the PNG was drawn with
    std::string legend_title;  // e.g. "depth (m, bed-normal)"
};

// <figure> with the image, the overlay, the legend and the figure's caption.
std::string map_figure_html(const MapFigure& figure, const MapOverlay& overlay);

// What every map of a set shares, said once: the hillshade, the overlay symbols, what "up"
// is (grid north of the CRS, or the chute's axes) and where the scale comes from.
std::string map_notes_html(const MapOverlay& overlay);

// The legend of a ramp as an HTML list of colour swatches and labels; a discrete ramp that
// leaves values up to its first break uncoloured says so (its swatch is the grey terrain);
// with no_terrain_data, an entry for the hatch of the cells outside the DEM's data.
std::string legend_html(const gis::ColorRamp& ramp, const std::string& title,
                        bool no_terrain_data = false);

}  // namespace avalanche
