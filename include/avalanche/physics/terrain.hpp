#pragma once
// Space-varying coefficients of the computational frame, precomputed once per
// scene (STYLE.md convention 4, Clawpack's aux arrays) and passed to kernels.
//
// Both frames reduce the model to one form (docs/theory.md):
//   dU/dt + dF/dx + dG/dy = S,
//   F = (hu, hu^2 + 1/2 k_x p_x h^2, huv),  G = (hv, huv, hv^2 + 1/2 k_y p_y h^2),
//   S = h (0, a_x, a_y) - friction,
//   friction: magnitude tan(delta) N against the true (along-surface) velocity,
//   N = g_n + c_xx u^2 + 2 c_xy u v + c_yy v^2 (clamped >= 0),
//   true speed^2 = u^2 + v^2 + (s_x u + s_y v)^2.
// Chute frame: a_x = g sin(zeta) - g cos(zeta) dz_b/dx, p = g_n = g cos(zeta),
//   c_xx = -dzeta/dx, s = 0 (bed-fitted coordinates, h bed-normal).
// DEM frame: horizontal grid, h vertical thickness, (u, v) horizontal velocity;
//   a = -g grad z / (1 + |grad z|^2), p_x = g cos^2(theta) / (1 + z_x^2),
//   g_n = g cos(theta), c = Hessian(z) / sqrt(1 + |grad z|^2), s = grad z.
//
// Terrain made on demand. A DEM frame's coefficients may be computed tile by tile
// where the solver first needs them (dem_frame.hpp): on a large DEM a small flow then
// never touches the memory of the terrain it does not reach (on the project's
// machines first touching memory, not computing, was most of the setup of a large
// scene). Every field but `elevation` then holds its values only over the tiles
// made so far (zero elsewhere); whoever reads them calls ensure() for the cells it
// reads first. The values are those of computing every cell at once, to the bit.
#include <array>
#include <cstddef>
#include <functional>
#include <memory>
#include <vector>

#include "avalanche/core/field.hpp"
#include "avalanche/core/grid.hpp"

namespace avalanche {

enum class Frame { chute, dem };

struct TerrainFields;

// The tiles of a terrain made on demand: which are made, and how to make one.
// ensure() may be called from several threads (batch scenarios share a scene): a
// mutex orders the making and the readers of a tile after it.
class TerrainTiles {
public:
    static constexpr int kTileCells = 64;  // a tile's width and height in cells
    // make(t, i0, i1, j0, j1) fills cells [i0, i1) x [j0, j1) of every on-demand field
    // of t and, where the range reaches an edge of the grid, the ghost cells beyond it.
    using Maker = std::function<void(TerrainFields&, int, int, int, int)>;
    TerrainTiles(const Grid& grid, Maker make);
    ~TerrainTiles();
    // Makes every tile meeting cells [i0, i1) x [j0, j1) (clamped to the grid) that is not
    // made yet.
    void ensure(TerrainFields& t, int i0, int i1, int j0, int j1);
    [[nodiscard]] std::size_t tiles_made() const;
    [[nodiscard]] std::size_t tiles() const { return made_.size(); }

private:
    struct Lock;
    int tiles_x_ = 0, tiles_y_ = 0, nx_ = 0, ny_ = 0;
    Maker make_;
    std::vector<unsigned char> made_;
    std::unique_ptr<Lock> lock_;
};

// The coefficients of one cell that the DEM frame computes from its slopes instead of
// storing them (TerrainFields::coefficients).
struct CellCoefficients {
    double ax, ay, px, py, gn;
};

struct TerrainFields {
    Frame frame = Frame::chute;
    // ax, ay, px, py, gn: empty in the DEM frame (has_metric), where they are functions of
    // sx, sy alone that every reader computes (coefficients(), dem_coefficients.hpp):
    // 40 bytes per cell fewer to make, keep and read.
    Field2D ax, ay;           // non-friction source acceleration (m/s^2)
    Field2D px, py;           // pressure coefficient without k, "g_z" (m/s^2)
    Field2D gn;               // bed-normal gravity for the friction load (m/s^2)
    Field2D cxx, cxy, cyy;    // curvature for the centripetal load (1/m); empty if none
    Field2D sx, sy;           // surface gradient for the true speed; empty in bed-fitted frames
    Field2D normal_thickness; // factor from the state's h to bed-normal thickness
    Field2D elevation;        // bed elevation (m); chute: height above the runout. Reports and the
                              // solver's energy cap use it: it must be the height whose gravity
                              // potential g z the accelerations ax, ay derive from. Always complete.
    bool has_curvature = false;
    bool has_metric = false;
    // With has_metric (the DEM frame): the g of ax, ay, px, py, gn and normal_thickness,
    // functions of sx, sy alone (dem_coefficients.hpp), which the solver's per-cell passes
    // compute from sx, sy (ax .. gn are not stored; normal_thickness is, for the products).
    double slope_gravity = 0.0;
    // Set when the fields are made on demand (see above; tiles not made yet hold zeros);
    // null when every value was computed at once (the chute frame, a copy).
    std::unique_ptr<TerrainTiles> on_demand;

    TerrainFields() = default;
    ~TerrainFields() = default;
    TerrainFields(TerrainFields&&) noexcept = default;
    TerrainFields& operator=(TerrainFields&&) noexcept = default;
    // A copy holds every value (the source's missing tiles are made first).
    TerrainFields(const TerrainFields& other);
    TerrainFields& operator=(const TerrainFields& other);

    // Allocates every field for the grid (curvature and metric only if asked).
    void allocate(const Grid& g, bool curvature, bool metric);
    // The same, for a terrain that varies only along x (the chute): every field stores the
    // one row all its rows read (Field2D::same_in_every_row), 80 bytes per cell fewer on
    // the chute. Without the metric. A writer of one cell gives that field every row.
    void allocate_same_in_every_row(const Grid& g, bool curvature);
    // Fills ghost cells by zero-gradient extension of every allocated field.
    void extend_to_ghosts();

    // Makes the values of cells [i0, i1) x [j0, j1) (clamped to the grid; with the ghost
    // cells beyond an edge the range reaches) if they are made on demand. Logically
    // const: the values are fixed by the scene; only when they are computed changes.
    void ensure(int i0, int i1, int j0, int j1) const;
    void ensure_everywhere() const;

    // ax, ay, px, py, gn of cell (i, j) (ghost cells included; made, see ensure): read where
    // they are stored, computed from sx, sy in the DEM frame.
    [[nodiscard]] CellCoefficients coefficients(int i, int j) const;
};

// Every field of TerrainFields derived from the elevation (all but `elevation`; the
// curvature and metric ones are empty where the frame has none): the one list that
// copies, ghost extensions and the DEM frame's tiles loop over, so that a field added
// to TerrainFields is added here and nowhere else.
inline constexpr std::array<Field2D TerrainFields::*, 11> kDerivedTerrainFields{
    &TerrainFields::ax,  &TerrainFields::ay,  &TerrainFields::px,
    &TerrainFields::py,  &TerrainFields::gn,  &TerrainFields::cxx,
    &TerrainFields::cxy, &TerrainFields::cyy, &TerrainFields::sx,
    &TerrainFields::sy,  &TerrainFields::normal_thickness};

}  // namespace avalanche
