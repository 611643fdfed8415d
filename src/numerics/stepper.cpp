#include "avalanche/numerics/stepper.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "avalanche/core/error.hpp"
#include "avalanche/numerics/cell_rows.hpp"
#include "avalanche/numerics/energy_cap.hpp"
#include "avalanche/numerics/face_flux_rows.hpp"

namespace avalanche {


Stepper::Stepper(const Grid& grid, const TerrainFields& terrain, const MaterialParams& material,
                 const NumericsParams& numerics, double h_min)
    : grid_(grid),
      terrain_(terrain),
      material_(material),
      numerics_(numerics),
      k_(earth_pressure_coefficients(material)),
      tan_delta_(material.tan_delta()),
      h_min_(h_min),
      k_max_(std::max({k_.kx_active, k_.kx_passive, k_.ky_given_kx_active_active, k_.ky_given_kx_active_passive,
                       k_.ky_given_kx_passive_active, k_.ky_given_kx_passive_passive})),
      energy_budget_(std::numeric_limits<double>::infinity()),
      edge_outflow_{std::vector<double>(static_cast<std::size_t>(grid.ny)),
                    std::vector<double>(static_cast<std::size_t>(grid.ny)),
                    std::vector<double>(static_cast<std::size_t>(grid.nx)),
                    std::vector<double>(static_cast<std::size_t>(grid.nx))} {
    // The per-cell passes compute the DEM frame's coefficients from the slopes with this g.
    if (terrain.has_metric && !(terrain.slope_gravity > 0.0))
        throw Error(ExitCode::internal, "Stepper: a terrain with slopes (sx, sy) needs its slope_gravity");
}

// ---------------------------------------------------------------- energy cap

// Per unit mass: kinetic energy, potential energy of the free surface above the
// cell (the vertical extent of a bed-normal thickness h_n is at most h_n g/g_n, exact
// in the chute frame, an over-estimate in the DEM frame), and the pressure energy
// 2 a^2 = 2 k g_n h_n that a free front can draw from the layer behind it (Ritter's
// front moves at 2 a0: (2 a0)^2 / 2 = 2 a0^2). Friction only removes energy.
double Stepper::energy_budget_of(const State& s) const {
    return energy_budget_in(s, ActiveBox{0, grid_.nx, 0, grid_.ny});
}

// The same over a box that holds every wet cell (step() passes the wet box, so that a
// small flow on a large grid does not scan the whole grid).
double Stepper::energy_budget_in(const State& s, const ActiveBox& wet) const {
    const double g = numerics_.gravity;
    terrain_.ensure(wet.i0, wet.i1, wet.j0, wet.j1);
    double budget = -std::numeric_limits<double>::infinity();
    // On the threads (the maximum is exact in any order): on one, the pass over the
    // first step's wet box was 0.5-0.6 % of benchmark (a)'s 50 steps on two threads.
    const bool threaded = wet.cells() >= kMinCellsPerThreadedStep;
#pragma omp parallel for reduction(max : budget) schedule(static) if (threaded)
    for (int j = wet.j0; j < wet.j1; ++j) {
        for (int i = wet.i0; i < wet.i1; ++i) {
            const double h = s.h(i, j);
            if (h <= 0.0) continue;
            const double u = s.hu(i, j) / h, v = s.hv(i, j) / h;
            double speed2 = u * u + v * v;
            if (terrain_.has_metric) {
                const double w = terrain_.sx(i, j) * u + terrain_.sy(i, j) * v;
                speed2 += w * w;
            }
            const double gn = terrain_.coefficients(i, j).gn;
            const double hn = h * terrain_.normal_thickness(i, j);
            const double e = 0.5 * speed2 + g * (terrain_.elevation(i, j) + hn * g / gn) + 2.0 * k_max_ * gn * hn;
            budget = std::max(budget, e);
        }
    }
    return budget;
}

// ---------------------------------------------------------------- active box

void Stepper::shrink_box_to_wet(const State& s, const ActiveBox& search) {
    ActiveBox wet{grid_.nx, -1, grid_.ny, -1};
    if (row_first_.size() != static_cast<std::size_t>(grid_.ny)) {
        row_first_.assign(static_cast<std::size_t>(grid_.ny), grid_.nx);
        row_last_.assign(static_cast<std::size_t>(grid_.ny), -1);
    }
    for (int j = search.j0; j < search.j1; ++j) {
        const double* h = s.h.row(j);
        row_first_[static_cast<std::size_t>(j)] = grid_.nx;
        row_last_[static_cast<std::size_t>(j)] = -1;
        // The first and the last wet cell, searched from either end: a row of a flow
        // is mostly wet, so neither search goes far.
        int first = search.i0;
        while (first < search.i1 && !(h[first] > 0.0)) ++first;
        if (first == search.i1) continue;
        int last = search.i1 - 1;
        while (!(h[last] > 0.0)) --last;
        // The bands' cells: those of material, or once the films are settled those at
        // least h_min thick, searched within the material (a whole row of films at
        // most, a few per cent of the work those films would take).
        int work_first = first, work_last = last;
        if (films_settled_) {
            while (work_first <= last && !is_wet(h[work_first], h_min_)) ++work_first;
            if (work_first <= last)
                while (!is_wet(h[work_last], h_min_)) --work_last;
        }
        if (work_first <= last) {
            row_first_[static_cast<std::size_t>(j)] = work_first;
            row_last_[static_cast<std::size_t>(j)] = work_last;
        }
        wet.i0 = std::min(wet.i0, first);
        wet.i1 = std::max(wet.i1, last + 1);
        wet.j0 = std::min(wet.j0, j);
        wet.j1 = std::max(wet.j1, j + 1);
    }
    if (wet.i1 < 0) wet = ActiveBox{0, 0, 0, 0};
    wet_box_ = wet;
    box_ = wet.widened(numerics_.active_margin, grid_.nx, grid_.ny);
    make_bands();
    // The kernels read the terrain of the box and of kGhostLayers cells beyond it (its
    // per-cell rows, per_cell_box); two more cells for good measure. Terrain made on
    // demand (terrain.hpp) is made here, before any kernel of the step reads it.
    if (!box_.empty()) {
        const ActiveBox read = box_.widened(kGhostLayers + 2, grid_.nx, grid_.ny);
        terrain_.ensure(read.i0, read.i1, read.j0, read.j1);
    }
}

// A band of rows of the box needs the columns of every cell that the box's margin
// would put in the box for the material of its rows: the cells within active_margin
// columns of a wet cell (h > 0) at most active_margin rows away. Outside those the
// advection over the whole box changes nothing: every cell and every cell its stencil
// reads is empty (h = hu = hv = 0), its fluxes are zero and its update gives it back
// (its regime aside, which advect() resets as the whole box would). So the bands
// give the whole box's result to the bit, whatever their height or number.
// Once the films are settled (films_settled_), the same holds with "at least h_min
// thick" for "wet": a film farther than the margin from every such cell, at rest with
// hu = hv = +0, lies between faces that are dry on both sides (zero fluxes) through
// both advections of an L S L step, whose thick cells move one cell each; the friction
// stage the bands skip would give it momentum that the second advection's update
// (thin cells keep none) and its thin-layer rule (no wet neighbour: +0) take away
// again; its regime is the regime at start (a film's velocity differences extend);
// and no kernel of the bands reads its momentum but through a dry face or a zero
// wetness weight. So the step gives it back unchanged, as the whole box does.
void Stepper::make_bands() {
    bands_.clear();
    const ActiveBox b = box_;
    if (b.empty()) return;
    if (whole_box_advection_) {
        bands_.push_back(b);
    } else {
        const int m = numerics_.active_margin;
        const int rows = kBandStrips * kStripRows;
        for (int j0 = b.j0; j0 < b.j1; j0 += rows) {
            const int j1 = std::min(j0 + rows, b.j1);
            int first = grid_.nx, last = -1;
            for (int j = std::max(j0 - m, wet_box_.j0); j < std::min(j1 + m, wet_box_.j1); ++j) {
                first = std::min(first, row_first_[static_cast<std::size_t>(j)]);
                last = std::max(last, row_last_[static_cast<std::size_t>(j)]);
            }
            ActiveBox band{b.i0, b.i0, j0, j1};  // nothing within reach: no columns
            if (last >= first) band = {std::max(first - m, b.i0), std::min(last + 1 + m, b.i1), j0, j1};
            // Merged with the band below where its columns would add little: a band's
            // first strip computes the stage rows it shares with the band below afresh
            // (advect()), about kRestartRows rows of its width.
            constexpr std::size_t kRestartRows = 8;
            if (!bands_.empty() && !bands_.back().empty() && !band.empty()) {
                ActiveBox& below = bands_.back();
                const ActiveBox both{std::min(below.i0, band.i0), std::max(below.i1, band.i1), below.j0, j1};
                const std::size_t restart = kRestartRows * static_cast<std::size_t>(band.i1 - band.i0);
                if (both.cells() <= below.cells() + band.cells() + restart) {
                    below = both;
                    continue;
                }
            }
            bands_.push_back(band);
        }
    }
    band_columns_.resize(static_cast<std::size_t>(b.j1 - b.j0));
    for (const ActiveBox& band : bands_)
        for (int j = band.j0; j < band.j1; ++j)
            band_columns_[static_cast<std::size_t>(j - b.j0)] = {band.i0, std::max(band.i0, band.i1)};
}

CellVector<RegimeFlags> Stepper::regime() const {
    CellVector<RegimeFlags> r(regime_.size());
    std::transform(regime_.begin(), regime_.end(), r.begin(), regime_of_stored);
    return r;
}

void Stepper::set_regime(const CellVector<RegimeFlags>& r) {
    regime_ = CellVector<StoredRegime>(r.size());
    std::transform(r.begin(), r.end(), regime_.begin(), stored_regime);
}

CellVector<HeldFlag> Stepper::held_at_rest() const { return held_quiet_; }

void Stepper::set_held_at_rest(CellVector<HeldFlag> held) {
    held_quiet_ = std::move(held);
    after_sources_ = false;
}

void Stepper::reset_active_box(const State& s) { reset_active_box(s, ActiveBox{0, grid_.nx, 0, grid_.ny}); }

void Stepper::reset_active_box(const State& s, const ActiveBox& holding) {
    films_settled_ = false;  // a state from outside: its films may move
    shrink_box_to_wet(s, holding.clipped(grid_.nx, grid_.ny));
}

// ---------------------------------------------------------------- boundaries

void Stepper::fill_ghosts(State& s) const { fill_ghosts_near(s, ActiveBox{0, grid_.nx, 0, grid_.ny}); }

// Only the ghosts the kernels can read: those within kGhostLayers + 2 cells of `near`
// (the advection reads at most kGhostLayers + 1 cells beyond the active box). On a
// 2000 x 2000 grid with a small flow, the full fill walked 2 x 4000 strided edge
// cells twice per step for nothing. Ghosts are written from interior cells only (the
// corners from edge-row ghosts filled first), so the values are those of a full fill.
void Stepper::fill_ghosts_near(State& s, const ActiveBox& box) const {
    const bool wall = numerics_.boundary == Boundary::wall;
    const int nx = grid_.nx, ny = grid_.ny;
    const ActiveBox near = box.empty() ? ActiveBox{0, nx, 0, ny} : box;  // e.g. advect() before any step
    constexpr int reach = kGhostLayers + 2;
    const bool west = near.i0 < reach, east = near.i1 > nx - reach;
    const bool south = near.j0 < reach, north = near.j1 > ny - reach;
    // Open: zero-gradient copy (inflow is removed at the faces afterwards).
    // Wall: mirror image with the normal momentum reversed.
    if (west || east) {
        const int ja = std::max(0, near.j0 - reach), jb = std::min(ny, near.j1 + reach);
        // Each row's ghosts are its own cells' images: the rows may go to the threads.
        // Every cell touched is on a row of its own (a page apart on wide grids): on
        // one thread this loop was 1.0-1.2 % of benchmark (a)'s run on two (four calls a step).
#pragma omp parallel for schedule(static) if (threaded_ && jb - ja >= kMinRowsPerThreadedGhostFill)
        for (int j = ja; j < jb; ++j) {
            for (int g = 1; g <= kGhostLayers; ++g) {
                const int w = wall ? g - 1 : 0, e = wall ? nx - g : nx - 1;
                if (west) {
                    s.h(-g, j) = s.h(w, j);
                    s.hu(-g, j) = wall ? -s.hu(w, j) : s.hu(w, j);
                    s.hv(-g, j) = s.hv(w, j);
                }
                if (east) {
                    s.h(nx - 1 + g, j) = s.h(e, j);
                    s.hu(nx - 1 + g, j) = wall ? -s.hu(e, j) : s.hu(e, j);
                    s.hv(nx - 1 + g, j) = s.hv(e, j);
                }
            }
        }
    }
    if (!south && !north) return;
    const int ia = std::max(-kGhostLayers, near.i0 - reach), ib = std::min(nx + kGhostLayers, near.i1 + reach);
    for (int g = 1; g <= kGhostLayers; ++g) {
        const int so = wall ? g - 1 : 0, no = wall ? ny - g : ny - 1;
        for (int i = ia; i < ib; ++i) {
            if (south) {
                s.h(i, -g) = s.h(i, so);
                s.hu(i, -g) = s.hu(i, so);
                s.hv(i, -g) = wall ? -s.hv(i, so) : s.hv(i, so);
            }
            if (north) {
                s.h(i, ny - 1 + g) = s.h(i, no);
                s.hu(i, ny - 1 + g) = s.hu(i, no);
                s.hv(i, ny - 1 + g) = wall ? -s.hv(i, no) : s.hv(i, no);
            }
        }
    }
}

// ---------------------------------------------------------------- time step

// Conservative celerity: the larger of the active and passive coefficients.
std::pair<double, double> Stepper::cfl_k() const {
    const double kx = std::max(k_.kx_active, k_.kx_passive);
    const double ky = std::max({k_.ky_given_kx_active_active, k_.ky_given_kx_active_passive,
                                k_.ky_given_kx_passive_active, k_.ky_given_kx_passive_passive});
    return {kx, ky};
}

// max over the wet cells i0 .. i1 - 1 of row j of (|u| + a_x)/dx and (|v| + a_y)/dy.
double Stepper::cfl_rate_of_row(const State& s, int j, int i0, int i1) const {
    const auto [kx, ky] = cfl_k();
    const CflRowTerrain t = terrain_.has_metric
                                ? CflRowTerrain{nullptr, nullptr, terrain_.sx.row(j),
                                                terrain_.sy.row(j), terrain_.slope_gravity}
                                : CflRowTerrain{terrain_.px.row(j), terrain_.py.row(j)};
    return cfl_rate_row(s.h.row(j), s.hu.row(j), s.hv.row(j), t, kx, ky, grid_.dx, grid_.dy, h_min_,
                        i0, i1);
}

double Stepper::dt_of_rate(double rate) const {
    return rate > 0.0 ? numerics_.cfl / rate : std::numeric_limits<double>::infinity();
}

double Stepper::stable_dt(const State& s) const {
    double rate = 0.0;  // max over cells of (|u| + a_x)/dx and (|v| + a_y)/dy
    const ActiveBox b = box_;
    // The rows' band columns differ in width, so the rows are handed out eight at a time
    // (here, in the thin-layer rule and the sources): a whole avaKot run at 5 m on two
    // threads 8.0-8.4 s against 8.3-8.5 s with equal shares of rows.
#pragma omp parallel for reduction(max : rate) schedule(dynamic, 8) if (threaded_)
    for (int j = b.j0; j < b.j1; ++j) {
        const auto [i0, i1] = band_columns_[static_cast<std::size_t>(j - b.j0)];
        if (i0 < i1) rate = std::max(rate, cfl_rate_of_row(s, j, i0, i1));
    }
    return dt_of_rate(rate);
}

void Stepper::step(State& s, double dt) {
    dt_of_last_step_.reset();
    // The wet area can grow by at most two cells per step; search a little beyond it.
    const ActiveBox search =
        wet_box_.empty() ? ActiveBox{0, grid_.nx, 0, grid_.ny} : wet_box_.widened(3, grid_.nx, grid_.ny);
    shrink_box_to_wet(s, search);
    if (box_.empty()) return;
    if (!budget_set_) set_energy_budget(energy_budget_in(s, wet_box_));
    // The work is the bands' (settled films left out, make_bands), not the box's.
    std::size_t band_cells = 0;
    for (const ActiveBox& band : bands_) band_cells += band.cells();
    threaded_ = band_cells >= kMinCellsPerThreadedStep;
    if (numerics_.splitting == Splitting::lsl) {
        advect(s, 0.5 * dt);
        apply_sources(s, dt);
        // The rows the last advection updates are every row stable_dt would read
        // (band_columns_ are the bands' columns, and the bands' strips cover their rows).
        take_cfl_rate_ = true;
        advect(s, 0.5 * dt);
        take_cfl_rate_ = false;
    } else {
        apply_sources(s, 0.5 * dt);
        advect(s, dt);
        // The friction stage is the last operator: it takes the rates (apply_sources).
        take_cfl_rate_ = true;
        apply_sources(s, 0.5 * dt);
        take_cfl_rate_ = false;
    }
    cell_updates_ += box_.cells();
    band_cell_updates_ += band_cells;
}

// ---------------------------------------------------------------- advection L(tau): advection.cpp

// Thin-layer rule (Wang & Li 2017 section 2.2.3): a cell thinner than h_min takes
// the velocity of its deepest wet neighbour, or stops if it has none. Every such cell
// of the bands is written, whatever its momentum was: the update relies on it and
// gives these cells none (UpdateRowParams::h_thin).
void Stepper::thin_layer_velocities(State& s) const {
    constexpr int kThinBlock = 16;
    const ActiveBox b = box_;
    const double hmin = h_min_;
#pragma omp parallel for schedule(dynamic, 8) if (threaded_)
    for (int j = b.j0; j < b.j1; ++j) {
        const double* hrow = s.h.row(j);
        const double* h_south = s.h.row(j - 1);  // ghost rows at the edges
        const double* h_north = s.h.row(j + 1);
        double* hu_row = s.hu.row(j);
        double* hv_row = s.hv.row(j);
        // The two common cases a block of kThinBlock cells from a at a time, with vector
        // compares (cell by cell, the tests were 3-5 % of a step): every cell at least
        // h_min thick (nothing to do), or every cell and every neighbour thinner (the
        // velocity is zero, as for a single such cell below). True when it is settled.
        const auto settle_block = [=](int a) {
            const int e = a + kThinBlock;  // a fixed trip count: the loops vectorise fully
            double wet = 0.0;
#pragma omp simd reduction(+ : wet)
            for (int k = a; k < e; ++k) wet += hrow[k] >= hmin ? 1.0 : 0.0;
            if (wet == kThinBlock) return true;
            if (wet != 0.0 || hrow[a - 1] >= hmin || hrow[e] >= hmin) return false;
            double wet_around = 0.0;
#pragma omp simd reduction(+ : wet_around)
            for (int k = a; k < e; ++k)
                wet_around += (h_south[k] >= hmin ? 1.0 : 0.0) + (h_north[k] >= hmin ? 1.0 : 0.0);
            if (wet_around != 0.0) return false;
#pragma omp simd
            for (int k = a; k < e; ++k) {
                hu_row[k] = hrow[k] * 0.0;
                hv_row[k] = hrow[k] * 0.0;
            }
            return true;
        };
        const auto [i0, i1] = band_columns_[static_cast<std::size_t>(j - b.j0)];
        for (int a = i0; a < i1; a += kThinBlock) {
            const int e = std::min(a + kThinBlock, i1);
            if (e - a == kThinBlock && settle_block(a)) continue;
            for (int i = a; i < e; ++i) {
                const double h = hrow[i];
                if (h >= hmin) continue;
                // No wet neighbour (most of the dry margin of the box): the velocity is
                // zero, as the search below would find.
                if (!(hrow[i - 1] >= hmin) && !(hrow[i + 1] >= hmin) && !(h_south[i] >= hmin) &&
                    !(h_north[i] >= hmin)) {
                    hu_row[i] = h * 0.0;
                    hv_row[i] = h * 0.0;
                    continue;
                }
                double best = hmin, u = 0.0, v = 0.0;
                int best_i = i, best_j = j;
                const int ni[4] = {i - 1, i + 1, i, i};
                const int nj[4] = {j, j, j - 1, j + 1};
                for (int n = 0; n < 4; ++n) {
                    const double hn = s.h(ni[n], nj[n]);  // ghosts hold the boundary images
                    if (hn >= best) {
                        best = hn;
                        u = s.hu(ni[n], nj[n]) / hn;
                        v = s.hv(ni[n], nj[n]) / hn;
                        best_i = std::clamp(ni[n], 0, grid_.nx - 1);
                        best_j = std::clamp(nj[n], 0, grid_.ny - 1);
                    }
                }
                // In the DEM frame the copied horizontal velocity means a different
                // along-surface speed on this cell's slope: keep the neighbour's.
                if (terrain_.has_metric && (u != 0.0 || v != 0.0)) {
                    const auto surface_speed = [&](int ii, int jj) {
                        const double w = terrain_.sx(ii, jj) * u + terrain_.sy(ii, jj) * v;
                        return std::sqrt(u * u + v * v + w * w);
                    };
                    const double here = surface_speed(i, j), there = surface_speed(best_i, best_j);
                    if (here > there) {
                        u *= there / here;
                        v *= there / here;
                    }
                }
                // The copied velocity must also respect this cell's energy cap (the
                // neighbour may lie lower, where more speed is allowed).
                if (u != 0.0 || v != 0.0) {
                    double speed2 = u * u + v * v;
                    if (terrain_.has_metric) {
                        const double w = terrain_.sx(i, j) * u + terrain_.sy(i, j) * v;
                        speed2 += w * w;
                    }
                    cap_speed(u, v, speed2, speed_cap2(terrain_.elevation(i, j)));
                }
                s.hu(i, j) = h * u;
                s.hv(i, j) = h * v;
            }
        }
    }
}

// ---------------------------------------------------------------- sources S(dt)

// Point-wise sources, friction last (MODEL.md 2.4, GeoClaw src2): tangential
// gravity first; then Coulomb friction of magnitude f = tan(delta) N dt against the
// true velocity, which stops the cell if |u| <= f and never reverses it.
void Stepper::apply_sources(State& s, double dt) {
    const ActiveBox b = box_;
    const bool rest = numerics_.rest_faces;
    if (rest && held_.size() != s.h.raw().size()) held_ = CellVector<HeldFlag>(s.h.raw().size());
    const int m = numerics_.source_substeps;
    const SourceRowParams p{dt / m, m, tan_delta_, numerics_.gravity, energy_budget_};
    const bool curv = terrain_.has_curvature, metric = terrain_.has_metric;
    const bool take_rate = take_cfl_rate_;
    double rate = 0.0;  // stable_dt's, of the rows as this stage leaves them
#pragma omp parallel for reduction(max : rate) schedule(dynamic, 8) if (threaded_)
    for (int j = b.j0; j < b.j1; ++j) {
        // The DEM frame stores no ax, ay, gn: the kernel computes them from sx, sy.
        const SourceRowTerrain t{metric ? nullptr : terrain_.ax.row(j),
                                 metric ? nullptr : terrain_.ay.row(j),
                                 metric ? nullptr : terrain_.gn.row(j),
                                 terrain_.elevation.row(j),
                                 curv ? terrain_.cxx.row(j) : nullptr,
                                 curv ? terrain_.cxy.row(j) : nullptr,
                                 curv ? terrain_.cyy.row(j) : nullptr,
                                 metric ? terrain_.sx.row(j) : nullptr,
                                 metric ? terrain_.sy.row(j) : nullptr,
                                 terrain_.slope_gravity};
        const auto [i0, i1] = band_columns_[static_cast<std::size_t>(j - b.j0)];
        if (i0 < i1) apply_sources_row(s.h.row(j), s.hu.row(j), s.hv.row(j), t, p, i0, i1);
        if (rest && i0 < i1)
            held_at_rest_row(s.h.row(j), s.hu.row(j), s.hv.row(j), h_min_,
                             held_.data() + s.h.index(0, j), i0, i1);
        if (take_rate && i0 < i1) rate = std::max(rate, cfl_rate_of_row(s, j, i0, i1));
    }
    if (take_rate) dt_of_last_step_ = dt_of_rate(rate);
    after_sources_ = true;
    films_settled_ = false;  // the films of the bands were given momentum
}

}  // namespace avalanche
