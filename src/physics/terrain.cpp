#include "avalanche/physics/terrain.hpp"

#include <algorithm>
#include <mutex>

#include "avalanche/core/state.hpp"
#include "avalanche/physics/dem_coefficients.hpp"

namespace avalanche {

struct TerrainTiles::Lock {
    std::mutex m;
};

TerrainTiles::TerrainTiles(const Grid& grid, Maker make)
    : tiles_x_((grid.nx + kTileCells - 1) / kTileCells),
      tiles_y_((grid.ny + kTileCells - 1) / kTileCells),
      nx_(grid.nx),
      ny_(grid.ny),
      make_(std::move(make)),
      made_(static_cast<std::size_t>(tiles_x_) * static_cast<std::size_t>(tiles_y_), 0),
      lock_(std::make_unique<Lock>()) {}

TerrainTiles::~TerrainTiles() = default;

void TerrainTiles::ensure(TerrainFields& t, int i0, int i1, int j0, int j1) {
    i0 = std::max(i0, 0);
    j0 = std::max(j0, 0);
    i1 = std::min(i1, nx_);
    j1 = std::min(j1, ny_);
    if (i1 <= i0 || j1 <= j0) return;
    const int ta = i0 / kTileCells, tb = (i1 - 1) / kTileCells;
    const int sa = j0 / kTileCells, sb = (j1 - 1) / kTileCells;
    const std::lock_guard<std::mutex> guard(lock_->m);
    for (int ty = sa; ty <= sb; ++ty)
        for (int tx = ta; tx <= tb; ++tx) {
            unsigned char& made = made_[static_cast<std::size_t>(ty) * tiles_x_ + tx];
            if (made) continue;
            make_(t, tx * kTileCells, std::min(nx_, (tx + 1) * kTileCells), ty * kTileCells,
                  std::min(ny_, (ty + 1) * kTileCells));
            made = 1;
        }
}

std::size_t TerrainTiles::tiles_made() const {
    const std::lock_guard<std::mutex> guard(lock_->m);
    return static_cast<std::size_t>(std::count(made_.begin(), made_.end(), 1));
}

TerrainFields::TerrainFields(const TerrainFields& other) { *this = other; }

TerrainFields& TerrainFields::operator=(const TerrainFields& other) {
    if (this == &other) return *this;
    other.ensure_everywhere();
    frame = other.frame;
    for (Field2D TerrainFields::*f : kDerivedTerrainFields) this->*f = other.*f;
    elevation = other.elevation;
    has_curvature = other.has_curvature;
    has_metric = other.has_metric;
    slope_gravity = other.slope_gravity;
    on_demand.reset();
    return *this;
}

namespace {
// Every field of t, each made by make(its value everywhere); curvature and metric only
// if asked.
template <class Make>
void allocate_fields(TerrainFields& t, Make make, bool curvature, bool metric) {
    t.ax = make(0.0);
    t.ay = make(0.0);
    t.px = make(0.0);
    t.py = make(0.0);
    t.gn = make(0.0);
    t.normal_thickness = make(1.0);
    t.elevation = make(0.0);
    t.has_curvature = curvature;
    t.has_metric = metric;
    t.cxx = curvature ? make(0.0) : Field2D();
    t.cxy = curvature ? make(0.0) : Field2D();
    t.cyy = curvature ? make(0.0) : Field2D();
    t.sx = metric ? make(0.0) : Field2D();
    t.sy = metric ? make(0.0) : Field2D();
}
}  // namespace

void TerrainFields::allocate(const Grid& g, bool curvature, bool metric) {
    // The caller writes every cell (an analytic terrain): huge pages (field_storage.hpp).
    const auto make = [&](double v) {
        Field2D f(g.nx, g.ny, kGhostLayers, v);
        f.advise_written_whole();
        return f;
    };
    allocate_fields(*this, make, curvature, metric);
}

void TerrainFields::allocate_same_in_every_row(const Grid& g, bool curvature) {
    const auto make = [&](double v) { return Field2D::same_in_every_row(g.nx, g.ny, kGhostLayers, v); };
    allocate_fields(*this, make, curvature, false);
}

void TerrainFields::extend_to_ghosts() {
    for (Field2D TerrainFields::*f : kDerivedTerrainFields)
        if (!(this->*f).empty()) (this->*f).extend_to_ghosts();
    if (!elevation.empty()) elevation.extend_to_ghosts();
}

// The fields are written through a cast of constness: what changes is the heap memory
// the fields own, never a const object, and only from "not computed yet" to the value
// the scene fixes.
void TerrainFields::ensure(int i0, int i1, int j0, int j1) const {
    if (on_demand) on_demand->ensure(const_cast<TerrainFields&>(*this), i0, i1, j0, j1);
}

void TerrainFields::ensure_everywhere() const {
    if (on_demand) ensure(0, elevation.nx(), 0, elevation.ny());
}

CellCoefficients TerrainFields::coefficients(int i, int j) const {
    if (has_metric) {
        const DemCoefficients c = dem_coefficients(sx(i, j), sy(i, j), slope_gravity);
        return {c.ax, c.ay, c.px, c.py, c.gn};
    }
    return {ax(i, j), ay(i, j), px(i, j), py(i, j), gn(i, j)};
}

}  // namespace avalanche
