#include "avalanche/numerics/stepper.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "avalanche/numerics/cell_rows.hpp"
#include "avalanche/numerics/face_flux_rows.hpp"

namespace avalanche {

namespace {
constexpr double kNoBound = std::numeric_limits<double>::max();

// Scales (u, v) so that the true speed^2 (speed2) does not exceed cap2; a cell
// with cap2 <= 0 lies above everything the material can reach and stops.
inline void cap_speed(double& u, double& v, double speed2, double cap2) {
    if (speed2 <= cap2) return;
    if (cap2 <= 0.0) {
        u = v = 0.0;
        return;
    }
    const double scale = std::sqrt(cap2 / speed2);
    u *= scale;
    v *= scale;
}
}  // namespace

Stepper::Stepper(const Grid& grid, const TerrainFields& terrain, const MaterialParams& material,
                 const NumericsParams& numerics, double h_min)
    : grid_(grid),
      terrain_(terrain),
      material_(material),
      numerics_(numerics),
      k_(earth_pressure_coefficients(material)),
      tan_delta_(material.tan_delta()),
      h_min_(h_min),
      cx_(grid.nx, grid.ny, kGhostLayers),
      cy_(grid.nx, grid.ny, kGhostLayers),
      pred_(grid),
      flux_x_(grid),
      flux_y_(grid),
      u_lo_(grid.nx, grid.ny, kGhostLayers, kNoBound),
      u_hi_(grid.nx, grid.ny, kGhostLayers, -kNoBound),
      v_lo_(grid.nx, grid.ny, kGhostLayers, kNoBound),
      v_hi_(grid.nx, grid.ny, kGhostLayers, -kNoBound),
      speed_hi_(grid.nx, grid.ny, kGhostLayers, 0.0),
      k_max_(std::max({k_.kx_active, k_.kx_passive, k_.ky_given_kx_active_active, k_.ky_given_kx_active_passive,
                       k_.ky_given_kx_passive_active, k_.ky_given_kx_passive_passive})),
      energy_budget_(std::numeric_limits<double>::infinity()) {}

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
    double budget = -std::numeric_limits<double>::infinity();
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
            const double gn = terrain_.gn(i, j);
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
    for (int j = search.j0; j < search.j1; ++j) {
        const double* h = s.h.row(j);
        int first = -1, last = -1;
        for (int i = search.i0; i < search.i1; ++i) {
            if (h[i] > 0.0) {
                if (first < 0) first = i;
                last = i;
            }
        }
        if (first >= 0) {
            wet.i0 = std::min(wet.i0, first);
            wet.i1 = std::max(wet.i1, last + 1);
            wet.j0 = std::min(wet.j0, j);
            wet.j1 = std::max(wet.j1, j + 1);
        }
    }
    if (wet.i1 < 0) wet = ActiveBox{0, 0, 0, 0};
    wet_box_ = wet;
    box_ = wet.widened(numerics_.active_margin, grid_.nx, grid_.ny);
}

void Stepper::reset_active_box(const State& s) {
    shrink_box_to_wet(s, ActiveBox{0, grid_.nx, 0, grid_.ny});
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

double Stepper::stable_dt(const State& s) const {
    // Conservative celerity: the larger of the active and passive coefficients.
    const double kx = std::max(k_.kx_active, k_.kx_passive);
    const double ky = std::max({k_.ky_given_kx_active_active, k_.ky_given_kx_active_passive,
                                k_.ky_given_kx_passive_active, k_.ky_given_kx_passive_passive});
    double rate = 0.0;  // max over cells of (|u| + a_x)/dx and (|v| + a_y)/dy
    const ActiveBox b = box_;
#pragma omp parallel for reduction(max : rate) schedule(static) if (threaded_)
    for (int j = b.j0; j < b.j1; ++j) {
        rate = std::max(rate, cfl_rate_row(s.h.row(j), s.hu.row(j), s.hv.row(j), terrain_.px.row(j),
                                           terrain_.py.row(j), kx, ky, grid_.dx, grid_.dy, h_min_, b.i0, b.i1));
    }
    return rate > 0.0 ? numerics_.cfl / rate : std::numeric_limits<double>::infinity();
}

void Stepper::step(State& s, double dt) {
    // The wet area can grow by at most two cells per step; search a little beyond it.
    const ActiveBox search =
        wet_box_.empty() ? ActiveBox{0, grid_.nx, 0, grid_.ny} : wet_box_.widened(3, grid_.nx, grid_.ny);
    shrink_box_to_wet(s, search);
    if (box_.empty()) return;
    if (!budget_set_) set_energy_budget(energy_budget_in(s, wet_box_));
    threaded_ = box_.cells() >= kMinCellsPerThreadedStep;
    if (numerics_.splitting == Splitting::lsl) {
        advect(s, 0.5 * dt);
        apply_sources(s, dt);
        advect(s, 0.5 * dt);
    } else {
        apply_sources(s, 0.5 * dt);
        advect(s, dt);
        apply_sources(s, 0.5 * dt);
    }
    cell_updates_ += box_.cells();
}

// ---------------------------------------------------------------- advection L(tau)

void Stepper::update_pressure_coefficients(const State& s) {
    const bool isotropic = material_.earth_pressure == EarthPressureModel::isotropic;
    const bool metric = terrain_.has_metric;
    const int ng = kGhostLayers;
    const int ia = std::max(box_.i0 - ng, -ng), ib = std::min(box_.i1 + ng, grid_.nx + ng);
    const int ja = std::max(box_.j0 - ng, -ng), jb = std::min(box_.j1 + ng, grid_.ny + ng);
    const double hmin = h_min_;
    const EarthPressureCoefficients kc = k_;
    const double kmax = k_max_;
    // Raw row pointers: the same arithmetic in the same order as through Field2D's
    // operator(), without its index computation per access (this loop touches 14 arrays).
    const auto vel = [hmin](double hh, double q) { return hh >= hmin && hh > 0.0 ? q / hh : 0.0; };
    // A vanishing gradient (at rest, or a uniformly moving block) counts as active:
    // passive there made a mass released from rest start with the passive k everywhere
    // and grow a period-4 pattern of regimes, with errors that rose under refinement
    // (docs/verification.md, finding 2). "Vanishing" is relative (1e-12 of the
    // velocities), so round-off cannot flip it.
    const auto extends = [](double lo, double hi) {
        return hi - lo >= -1e-12 * std::max(std::abs(lo), std::abs(hi));
    };
#pragma omp parallel for schedule(static) if (threaded_)
    for (int j = ja; j < jb; ++j) {
        // Central differences, clamped at the padding.
        const int jm = std::max(j - 1, -ng), jp = std::min(j + 1, grid_.ny + ng - 1);
        const double* h = s.h.row(j);
        const double* hu = s.hu.row(j);
        const double* hv = s.hv.row(j);
        const double* h_s = s.h.row(jm);
        const double* hv_s = s.hv.row(jm);
        const double* h_n = s.h.row(jp);
        const double* hv_n = s.hv.row(jp);
        const double* px = terrain_.px.row(j);
        const double* py = terrain_.py.row(j);
        const double* gn = terrain_.gn.row(j);
        const double* nt = terrain_.normal_thickness.row(j);
        const double* tsx = metric ? terrain_.sx.row(j) : nullptr;
        const double* tsy = metric ? terrain_.sy.row(j) : nullptr;
        double* cx = cx_.row(j);
        double* cy = cy_.row(j);
        double* ulo = u_lo_.row(j);
        double* uhi = u_hi_.row(j);
        double* vlo = v_lo_.row(j);
        double* vhi = v_hi_.row(j);
        double* shi = speed_hi_.row(j);
        for (int i = ia; i < ib; ++i) {
            const double hh = h[i];
            if (isotropic) {
                cx[i] = px[i];
                cy[i] = py[i];
            } else {
                // Active where the flow extends (du/dx > 0), passive where it compresses
                // (Wang & Li 2017 after eq. 3).
                const int im = std::max(i - 1, -ng), ip = std::min(i + 1, grid_.nx + ng - 1);
                const bool x_active = extends(vel(h[im], hu[im]), vel(h[ip], hu[ip]));
                const bool y_active = extends(vel(h_s[i], hv_s[i]), vel(h_n[i], hv_n[i]));
                cx[i] = kc.kx(x_active) * px[i];
                cy[i] = kc.ky(x_active, y_active) * py[i];
            }
            // Riemann invariants u -/+ 2a bound the velocities any Riemann fan
            // started here can produce (the invariant domain of the system).
            if (hh >= hmin && hh > 0.0) {
                const double u = hu[i] / hh, v = hv[i] / hh;
                const double ax = 2.0 * std::sqrt(cx[i] * hh), ay = 2.0 * std::sqrt(cy[i] * hh);
                ulo[i] = u - ax;
                uhi[i] = u + ax;
                vlo[i] = v - ay;
                vhi[i] = v + ay;
                // Along-surface speed plus the along-surface dry-front celerity
                // 2 sqrt(k g_n h_n): frame-independent (docs/numerics.md, step 8).
                double speed2 = u * u + v * v;
                if (metric) {
                    const double w = tsx[i] * u + tsy[i] * v;
                    speed2 += w * w;
                }
                shi[i] = std::sqrt(speed2) + 2.0 * std::sqrt(kmax * gn[i] * hh * nt[i]);
            } else {
                ulo[i] = vlo[i] = kNoBound;
                uhi[i] = vhi[i] = -kNoBound;
                shi[i] = 0.0;
            }
        }
    }
}

namespace {

// Views of a state along one direction: normal and tangential momentum.
struct DirectionalView {
    const double* h;
    const double* qn;
    const double* qt;
};

DirectionalView along(const State& s, bool along_x) {
    return {s.h.raw().data(), (along_x ? s.hu : s.hv).raw().data(), (along_x ? s.hv : s.hu).raw().data()};
}

struct DirectionalSink {
    double* h;
    double* qn;
    double* qt;
};

DirectionalSink along(State& s, bool along_x) {
    return {s.h.raw().data(), (along_x ? s.hu : s.hv).raw().data(), (along_x ? s.hv : s.hu).raw().data()};
}

}  // namespace

// First-order Godunov half step in one direction, the transverse predictor of
// Wang & Li (2017) eqs. 6-8: for the x-fluxes the states are advanced by tau/2 in y.
void Stepper::godunov_predictor(const State& s, double tau, bool along_x) {
    // along_x == false: predictor in y, used by the x-fluxes, computed on
    // columns [i0-2, i1+2) and rows [j0, j1); faces j in [j0, j1].
    // along_x == true: predictor in x for the y-fluxes, rows [j0-2, j1+2).
    // Both write pred_ (the x-fluxes are computed before the x predictor overwrites
    // it) and use flux_y_ as scratch for their first-order fluxes (the y-fluxes are
    // computed last): one predicted state and no flux field of their own.
    const int ng = kGhostLayers;
    const ActiveBox b = box_;
    State& flux = flux_y_;
    State& pred = pred_;
    const Field2D& c = along_x ? cx_ : cy_;
    const std::ptrdiff_t off = along_x ? 1 : s.h.stride();
    const double ratio = 0.5 * tau / (along_x ? grid_.dx : grid_.dy);
    const int ia = along_x ? b.i0 : std::max(b.i0 - ng, -ng);
    const int ib = along_x ? b.i1 : std::min(b.i1 + ng, grid_.nx + ng);
    const int ja = along_x ? std::max(b.j0 - ng, -ng) : b.j0;
    const int jb = along_x ? std::min(b.j1 + ng, grid_.ny + ng) : b.j1;
    const DirectionalView q = along(s, along_x);
    const DirectionalSink f = along(flux, along_x);
    const DirectionalSink p = along(pred, along_x);
    const double* cc = c.raw().data();
    const double hd = h_min_;
    // Faces: the face "before" cell k lies between k - off and k.
    const int fib = along_x ? ib + 1 : ib, fjb = along_x ? jb : jb + 1;
    const FaceRowInput in{q.h, q.qn, q.qt, cc, off};
    const FaceRowOutput out{f.h, f.qn, f.qt};
#pragma omp parallel for schedule(static) if (threaded_)
    for (int j = ja; j < fjb; ++j) hllc_face_row(in, out, s.h.index(ia, j), fib - ia, hd);
    const FaceRowOutput predicted{p.h, p.qn, p.qt};
#pragma omp parallel for schedule(static) if (threaded_)
    for (int j = ja; j < jb; ++j) predictor_row(in, out, ratio, predicted, s.h.index(ia, j), ib - ia);
}

// Face fluxes in one direction over the active box: WAF-TVD on the predicted
// states (Wang & Li 2017 eq. 9; the face flux is waf_face_flux in waf_face.hpp) or
// first-order HLLC on the current state, one row of faces at a time by the
// vectorised row kernels (face_flux_rows.hpp, bitwise the scalar kernels).
void Stepper::face_fluxes(const State& s, const State& predicted, double tau, bool along_x, bool waf) {
    const ActiveBox b = box_;
    State& flux = along_x ? flux_x_ : flux_y_;
    const Field2D& c = along_x ? cx_ : cy_;
    const std::ptrdiff_t off = along_x ? 1 : s.h.stride();
    const double dt_dx = tau / (along_x ? grid_.dx : grid_.dy);
    const DirectionalView q = along(waf ? predicted : s, along_x);
    const DirectionalSink f = along(flux, along_x);
    const FaceRowInput in{q.h, q.qn, q.qt, c.raw().data(), off};
    const FaceRowOutput out{f.h, f.qn, f.qt};
    const double hd = h_min_;
    const int fib = along_x ? b.i1 + 1 : b.i1, fjb = along_x ? b.j1 : b.j1 + 1;
    const int n = fib - b.i0;
    const Limiter lim = numerics_.limiter;
#pragma omp parallel for schedule(static) if (threaded_)
    for (int j = b.j0; j < fjb; ++j) {
        const std::ptrdiff_t k0 = s.h.index(b.i0, j);
        if (waf)
            waf_face_row(in, out, k0, n, hd, dt_dx, lim);
        else
            hllc_face_row(in, out, k0, n, hd);
    }
}

// Walls pass no mass and no tangential momentum; open edges pass only outflow.
void Stepper::fix_boundary_faces(const State& s) {
    const bool wall = numerics_.boundary == Boundary::wall;
    const ActiveBox b = box_;
    const auto fix = [&](State& flux, int i, int j, double outward_sign, bool x_face) {
        double& fh = flux.h(i, j);
        double& fn = x_face ? flux.hu(i, j) : flux.hv(i, j);
        double& ft = x_face ? flux.hv(i, j) : flux.hu(i, j);
        if (wall || fh * outward_sign < 0.0) {
            // Wall flux: keep the normal momentum (pressure and reflection), no mass.
            fh = 0.0;
            ft = 0.0;
            if (!wall) {
                // Inflow at an open edge is refused; the interior's pressure acts as at a wall.
                const int ii = x_face ? (outward_sign < 0 ? 0 : grid_.nx - 1) : i;
                const int jj = x_face ? j : (outward_sign < 0 ? 0 : grid_.ny - 1);
                const double h = s.h(ii, jj) >= h_min_ ? s.h(ii, jj) : 0.0;
                fn = 0.5 * (x_face ? cx_(ii, jj) : cy_(ii, jj)) * h * h;
            }
        }
    };
    if (b.i0 == 0)
        for (int j = b.j0; j < b.j1; ++j) fix(flux_x_, 0, j, -1.0, true);
    if (b.i1 == grid_.nx)
        for (int j = b.j0; j < b.j1; ++j) fix(flux_x_, grid_.nx, j, 1.0, true);
    if (b.j0 == 0)
        for (int i = b.i0; i < b.i1; ++i) fix(flux_y_, i, 0, -1.0, false);
    if (b.j1 == grid_.ny)
        for (int i = b.i0; i < b.i1; ++i) fix(flux_y_, i, grid_.ny, 1.0, false);
}

// Positivity and the thin-layer rule, conservatively: each face flux is scaled by
// the factor of its donor cell (the cell its mass leaves), chosen so that no cell
// exports more than it holds; thin cells (h < h_min) export nothing. Every face
// flux is then added to one cell and subtracted from the other, so the volume
// changes only by what crosses the open edges.
void Stepper::limit_and_update(State& s, double tau) {
    const ActiveBox b = box_;
    const double rx = tau / grid_.dx, ry = tau / grid_.dy;
    const double hmin = h_min_;
    const std::ptrdiff_t sx = 1, sy = s.h.stride();
    const double* fxh = flux_x_.h.raw().data();
    const double* fyh = flux_y_.h.raw().data();
    // The donor factors live in the predicted state's depth field, free once the face
    // fluxes exist (8 bytes per cell less). Faces reach one cell beyond the box; that
    // ring is dry, so its faces carry no mass, but it is set to 1 so that no stale
    // value can ever scale a flux.
    double* factor = pred_.h.raw().data();
    {
        const int ia = b.i0 - 1, ib = b.i1, ja = b.j0 - 1, jb = b.j1;  // ring: i in [ia, ib], j in [ja, jb]
        for (int i = ia; i <= ib; ++i) factor[s.h.index(i, ja)] = factor[s.h.index(i, jb)] = 1.0;
        for (int j = ja; j <= jb; ++j) factor[s.h.index(ia, j)] = factor[s.h.index(ib, j)] = 1.0;
    }
    double* hh = s.h.raw().data();
    double* hu = s.hu.raw().data();
    double* hv = s.hv.raw().data();
#pragma omp parallel for schedule(static) if (threaded_)
    for (int j = b.j0; j < b.j1; ++j) {
        for (int i = b.i0; i < b.i1; ++i) {
            const std::ptrdiff_t k = s.h.index(i, j);
            const double out = rx * (std::max(fxh[k + sx], 0.0) + std::max(-fxh[k], 0.0)) +
                               ry * (std::max(fyh[k + sy], 0.0) + std::max(-fyh[k], 0.0));
            double f = 1.0;
            if (hh[k] < hmin) f = 0.0;
            else if (out > hh[k]) f = hh[k] / out;
            factor[k] = f;
        }
    }
    // Each face is scaled by its donor's factor where it is used, so both cells of a
    // face compute the same product (x * 1 == x exactly for the unscaled faces) and
    // the fluxes need no second pass. A zero mass flux has no donor: its momentum
    // (the pressure of a wall face) passes unscaled.
    const auto donor = [factor](const double* fh, std::ptrdiff_t k, std::ptrdiff_t off) {
        return fh[k] == 0.0 ? 1.0 : factor[fh[k] > 0.0 ? k - off : k];
    };

    const double* fxu = flux_x_.hu.raw().data();
    const double* fxv = flux_x_.hv.raw().data();
    const double* fyu = flux_y_.hu.raw().data();
    const double* fyv = flux_y_.hv.raw().data();
    const bool metric = terrain_.has_metric;
    const double* elev = terrain_.elevation.raw().data();
    const double* tsx = metric ? terrain_.sx.raw().data() : nullptr;
    const double* tsy = metric ? terrain_.sy.raw().data() : nullptr;
    const double* ulo_f = u_lo_.raw().data();
    const double* uhi_f = u_hi_.raw().data();
    const double* vlo_f = v_lo_.raw().data();
    const double* vhi_f = v_hi_.raw().data();
    const double* shi_f = speed_hi_.raw().data();
    // Min / max over the 3 x 3 block around k (exact, so the order does not matter).
    const auto min9 = [sy](const double* f, std::ptrdiff_t k) {
        double m = kNoBound;
        for (std::ptrdiff_t r = k - sy; r <= k + sy; r += sy) m = std::min({m, f[r - 1], f[r], f[r + 1]});
        return m;
    };
    const auto max9 = [sy](const double* f, std::ptrdiff_t k, double init) {
        double m = init;
        for (std::ptrdiff_t r = k - sy; r <= k + sy; r += sy) m = std::max({m, f[r - 1], f[r], f[r + 1]});
        return m;
    };
#pragma omp parallel for schedule(static) if (threaded_)
    for (int j = b.j0; j < b.j1; ++j) {
        for (int i = b.i0; i < b.i1; ++i) {
            const std::ptrdiff_t k = s.h.index(i, j);
            // Conservative update, U -= tau/dx dF + tau/dy dG (Wang & Li 2017 eq. 5),
            // with the scaled fluxes.
            const double fw = donor(fxh, k, sx), fe = donor(fxh, k + sx, sx);
            const double fs = donor(fyh, k, sy), fn = donor(fyh, k + sy, sy);
            double hn = hh[k] - rx * (fxh[k + sx] * fe - fxh[k] * fw) - ry * (fyh[k + sy] * fn - fyh[k] * fs);
            // The donor factor bounds the export by h; what is left is round-off.
            if (hn < 0.0) hn = 0.0;
            hh[k] = hn;
            double qu = hu[k] - (rx * (fxu[k + sx] * fe - fxu[k] * fw) + ry * (fyu[k + sy] * fn - fyu[k] * fs));
            double qv = hv[k] - (rx * (fxv[k + sx] * fe - fxv[k] * fw) + ry * (fyv[k + sy] * fn - fyv[k] * fs));
            // Invariant-domain bound: the new velocity of a cell must lie within the
            // range of the Riemann invariants u -/+ 2a of the cell and its eight
            // neighbours before the update (the unsplit predictor couples the
            // diagonals). Smooth wet flow never reaches the bound; near-vacuum cells
            // between diverging flows, where the limited fluxes act on a vanishing
            // mass, are clamped to it.
            if (hn <= 0.0) {
                hu[k] = hv[k] = 0.0;
                continue;
            }
            double u = qu / hn, v = qv / hn;
            // The 3 x 3 range contains the cell's own: a velocity inside its own range
            // (nearly every wet cell) needs no neighbour (and a cell that was wet has a
            // wet cell around). Only the others look at the nine.
            if (!(ulo_f[k] <= u && u <= uhi_f[k] && vlo_f[k] <= v && v <= vhi_f[k])) {
                const double ulo = min9(ulo_f, k), uhi = max9(uhi_f, k, -kNoBound);
                if (ulo > uhi) {  // no wet cell around: nothing can have moved it
                    hu[k] = hv[k] = 0.0;
                    continue;
                }
                const double vlo = min9(vlo_f, k), vhi = max9(vhi_f, k, -kNoBound);
                if (u < ulo || u > uhi) u = std::clamp(u, ulo, uhi);
                if (v < vlo || v > vhi) v = std::clamp(v, vlo, vhi);
            }
            // The along-surface speed is bounded the same way. In the DEM frame the
            // fluxes carry horizontal momentum, and horizontal momentum moved onto a
            // much steeper cell (the foot of a cliff) would gain along-surface speed,
            // i.e. energy, without bound: the material meeting a slope break keeps at
            // most the speed it arrived with.
            double speed2 = u * u + v * v;
            if (metric) {
                const double w = tsx[k] * u + tsy[k] * v;
                speed2 += w * w;
            }
            if (speed2 > shi_f[k] * shi_f[k]) {  // again the own bound first
                const double speed_bound = max9(shi_f, k, 0.0);
                if (speed2 > speed_bound * speed_bound) {
                    const double scale = speed_bound / std::sqrt(speed2);
                    u *= scale;
                    v *= scale;
                    speed2 = speed_bound * speed_bound;
                }
            }
            // The energy cap: the invariant-domain bound above is local and can ratchet
            // up by 2a per step where momentum piles onto a steep cell; this one cannot.
            cap_speed(u, v, speed2, speed_cap2(elev[k]));
            hu[k] = hn * u;
            hv[k] = hn * v;
        }
    }
    // Volume through the open edges, after scaling.
    const auto outflow = [&](const double* fh, std::ptrdiff_t k, std::ptrdiff_t off, double sign) {
        return std::max(sign * (fh[k] * donor(fh, k, off)), 0.0);
    };
    double out = 0.0;
    if (b.i0 == 0)
        for (int j = b.j0; j < b.j1; ++j) out += outflow(fxh, s.h.index(0, j), sx, -1.0) * tau * grid_.dy;
    if (b.i1 == grid_.nx)
        for (int j = b.j0; j < b.j1; ++j) out += outflow(fxh, s.h.index(grid_.nx, j), sx, 1.0) * tau * grid_.dy;
    if (b.j0 == 0)
        for (int i = b.i0; i < b.i1; ++i) out += outflow(fyh, s.h.index(i, 0), sy, -1.0) * tau * grid_.dx;
    if (b.j1 == grid_.ny)
        for (int i = b.i0; i < b.i1; ++i) out += outflow(fyh, s.h.index(i, grid_.ny), sy, 1.0) * tau * grid_.dx;
    outflow_volume_ += out;
}

// Thin-layer rule (Wang & Li 2017 section 2.2.3): a cell thinner than h_min takes
// the velocity of its deepest wet neighbour, or stops if it has none.
void Stepper::thin_layer_velocities(State& s) const {
    const ActiveBox b = box_;
    const double hmin = h_min_;
#pragma omp parallel for schedule(static) if (threaded_)
    for (int j = b.j0; j < b.j1; ++j) {
        const double* hrow = s.h.row(j);
        for (int i = b.i0; i < b.i1; ++i) {
            const double h = hrow[i];
            if (h >= hmin) continue;  // the common case: one load, one compare
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

void Stepper::advect(State& s, double tau) {
    fill_ghosts_near(s, box_);
    update_pressure_coefficients(s);
    const bool waf = numerics_.scheme == Scheme::waf;
    if (waf) godunov_predictor(s, tau, /*along_x=*/false);  // states for the x-fluxes
    face_fluxes(s, pred_, tau, /*along_x=*/true, waf);
    if (waf) godunov_predictor(s, tau, /*along_x=*/true);   // states for the y-fluxes
    face_fluxes(s, pred_, tau, /*along_x=*/false, waf);
    fix_boundary_faces(s);
    limit_and_update(s, tau);
    fill_ghosts_near(s, box_);
    thin_layer_velocities(s);
}

// ---------------------------------------------------------------- sources S(dt)

// Point-wise sources, friction last (MODEL.md 2.4, GeoClaw src2): tangential
// gravity first; then Coulomb friction of magnitude f = tan(delta) N dt against the
// true velocity, which stops the cell if |u| <= f and never reverses it.
void Stepper::apply_sources(State& s, double dt) const {
    const ActiveBox b = box_;
    const int m = numerics_.source_substeps;
    const SourceRowParams p{dt / m, m, tan_delta_, numerics_.gravity, energy_budget_};
    const bool curv = terrain_.has_curvature, metric = terrain_.has_metric;
#pragma omp parallel for schedule(static) if (threaded_)
    for (int j = b.j0; j < b.j1; ++j) {
        const SourceRowTerrain t{terrain_.ax.row(j),
                                 terrain_.ay.row(j),
                                 terrain_.gn.row(j),
                                 terrain_.elevation.row(j),
                                 curv ? terrain_.cxx.row(j) : nullptr,
                                 curv ? terrain_.cxy.row(j) : nullptr,
                                 curv ? terrain_.cyy.row(j) : nullptr,
                                 metric ? terrain_.sx.row(j) : nullptr,
                                 metric ? terrain_.sy.row(j) : nullptr};
        apply_sources_row(s.h.row(j), s.hu.row(j), s.hv.row(j), t, p, b.i0, b.i1);
    }
}

}  // namespace avalanche
