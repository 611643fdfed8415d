// The advection operator L(tau) of the stepper (stepper.hpp), computed strip by strip.
//
// The operator has seven stages: pressure coefficients and invariant bounds per cell,
// the transverse predictor in y and the WAF x-fluxes, the predictor in x and the WAF
// y-fluxes, the boundary faces, the donor factors, and the conservative update. Here
// the active box is cut into bands of rows, each as wide as its rows' material needs
// (Stepper::make_bands), the bands into strips of kStripRows rows, and one thread runs
// all stages for one strip into buffers of a few rows that stay in its cache, so the
// stage fields need no grid-sized storage and only the state, the terrain and the
// updated state cross memory (docs/numerics.md, "Implementation notes", "Active region").
//
// A strip's update needs the stages on up to four rows beyond it. A thread takes
// consecutive strips and hands the rows each stage field needs from one strip to the
// next of the same band (StripBuffers::carry_rows); only the first strip of such a
// segment computes them afresh, with the same inputs and expressions, so every value
// is the one the whole-box passes computed and the result does not depend on the
// strip height, the bands or the thread count. A strip's updated rows go straight
// into the state: after the update nothing of the strip's own rows is read again, by
// it or by the segment's next strip (which reads the stage rows it is handed). Only
// the rows another segment's strip reads afresh, five at each inner end of a segment
// (kStateRowsReadBeyond), wait in the thread's buffers until every segment is done
// (advect()).
#include <omp.h>

#include <algorithm>
#include <cassert>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>
#include <tuple>
#include <vector>

#include "avalanche/numerics/cell_rows.hpp"
#include "avalanche/numerics/face_flux_rows.hpp"
#include "avalanche/numerics/stepper.hpp"
#include "avalanche/numerics/strip_claims.hpp"
#include "avalanche/numerics/update_rows.hpp"

namespace avalanche {

namespace {
// The rows on either side of a regime row whose state the regime rule reads
// (regime_row_into: its terms of rows r - 2 .. r + 2). With the per-cell stage's rows,
// three beyond a strip's own, they make the five state rows beyond its own that a
// strip reads (Stepper::kStateRowsReadBeyond; the velocity quotients reach four).
constexpr int kRegimeTermsReach = 2;

// Runs run(a, b) over the columns [ia, ib) in two parts, cut at the first column of a
// cache line (column 0 starts one: Field2D::column0, StripBuffers::k), for the row
// kernels whose result for a column does not depend on where their loop starts: the
// per-cell stage and the y-faces start two ghost columns before column 0, and their
// vector loads then straddled two lines each (case (a): WAF 6 % faster for column 0
// on a line, docs/performance.md).
template <class Run>
void from_line_start(int ia, int ib, Run&& run) {
    constexpr int line = Field2D::kRowAlignment;
    const int a = std::min(ia + ((-ia) % line + line) % line, ib);
    if (ia < a) run(ia, a);
    if (a < ib) run(a, ib);
}

// The positions [first, S + end_beyond) of a strip's arrays, rows(S) rows, for strips of
// S rows (StripBuffers::allocate says what each holds); count: the arrays that have them
// (allocate checks it), so that strip_rows_for counts the bytes allocate gives.
struct StripArrayRows {
    int first, end_beyond, count;
    [[nodiscard]] constexpr int rows(int S) const { return S + end_beyond - first; }
};
constexpr StripArrayRows kVelocityRows{0, 9, 2}, kPerCellRows{1, 7, 9}, kXFaceRows{3, 5, 4},
    kYFaceRows{3, 6, 3}, kOutRows{4, 4, 3}, kYPredictorRows{3, 6, 3}, kXPredictorRows{1, 7, 6};

// The bytes per column of a strip's arrays for strips of S rows.
constexpr std::size_t strip_bytes_per_column(int S, bool predictors) {
    std::size_t rows = 0;
    for (const StripArrayRows& a : {kVelocityRows, kPerCellRows, kXFaceRows, kYFaceRows, kOutRows})
        rows += static_cast<std::size_t>(a.count * a.rows(S));
    if (predictors)
        for (const StripArrayRows& a : {kYPredictorRows, kXPredictorRows})
            rows += static_cast<std::size_t>(a.count * a.rows(S));
    return rows * sizeof(double);
}
}  // namespace

int Stepper::strip_rows_for(int columns, bool waf) {
    int rows = kStripRows;
    const auto bytes = [&](int S) {
        return strip_bytes_per_column(S, waf) * static_cast<std::size_t>(columns);
    };
    while (rows > kFewestStripRows && bytes(rows) > kStripBufferBytes) rows /= 2;
    return rows;
}

void Stepper::set_strip_rows(int rows) {
    if (rows < 0 || rows > kStripRows)
        throw std::invalid_argument("Stepper::set_strip_rows: " + std::to_string(rows) +
                                    " rows; expected 0 (by width) or 1 to " +
                                    std::to_string(kStripRows));
    fixed_strip_rows_ = rows;
}

void Stepper::StripBuffers::allocate(std::ptrdiff_t row_stride, int column_zero, int strip_rows,
                                     bool predictors) {
    stride = row_stride;
    column0 = column_zero;
    rows = strip_rows + 8;
    // Each array's positions, from the row ranges of advect_strip for a strip [J, J + S)
    // at position 4 (base J - 4), with what its readers reach beyond them:
    // - su, sv: the velocity rows [J - 4, J + S + 5) (the last for the next strip only:
    //   advect_strip, step 1).
    // - The per-cell stage (cx .. speed_hi) and the x-predictor (pred_*): rows
    //   [J - 3, J + S + 3), the y-faces' four-cell stencils [J - 3, J + S + 2) included.
    // - yfo_*: the y-predictor's face rows J - 1 .. J + S + 1.
    // - fx_*, factor: rows J - 1 .. J + S (the update's and the edges' reach).
    // - fy_*: face rows J - 1 .. J + S + 1 (the donor factors of row J + S read the last).
    // - out_*: the strip's own rows.
    // The rows carry_rows moves lie within these. Fresh arrays of untouched zeros
    // (PageVector): a stage's first write of a column makes its pages. The bounds' "no
    // bound" is written by cover_columns. The first-order scheme has no predictors: their
    // nine arrays stay empty.
    const int S = strip_rows;
    // Without `used`, the arrays get no rows (empty).
    const auto make = [&](std::initializer_list<StripRows*> arrays, StripArrayRows r,
                          bool used = true) {
        assert(arrays.size() == static_cast<std::size_t>(r.count));
        for (StripRows* a : arrays) a->allocate(stride, r.first, r.first + (used ? r.rows(S) : 0));
    };
    make({&su, &sv}, kVelocityRows);
    make({&cx, &cy, &ax, &ay, &u_lo, &u_hi, &v_lo, &v_hi, &speed_hi}, kPerCellRows);
    make({&fx_h, &fx_hu, &fx_hv, &factor}, kXFaceRows);
    make({&fy_h, &fy_hu, &fy_hv}, kYFaceRows);
    make({&out_h, &out_hu, &out_hv}, kOutRows);
    make({&yfo_h, &yfo_qn, &yfo_qt}, kYPredictorRows, predictors);
    make({&pred_h, &pred_hu, &pred_hv, &pred_u, &pred_v, &pred_a}, kXPredictorRows, predictors);
    bounds_c0 = bounds_c1 = 0;
    for (auto* a : {&row_h, &row_hu, &row_hv, &row_u, &row_v, &row_a})
        a->assign(static_cast<std::size_t>(stride), 0.0);
    regime_row.assign(static_cast<std::size_t>(stride), kRegimeAtStart);
    for (auto* a : {&term_wet, &term_still_x, &term_still_y})
        a->assign(static_cast<std::size_t>(stride) * kRegimeRingRows, 0.0);
    held_regime.assign(static_cast<std::size_t>(stride) * 2 * kRegimeHeldRows, kRegimeAtStart);
    held_rows.reserve(2 * kRegimeHeldRows);
    held_cols.reserve(2 * kRegimeHeldRows);
}

void Stepper::StripBuffers::cover_columns(int c0, int c1) {
    c0 = std::max(c0, 0);
    c1 = std::min(c1, static_cast<int>(stride));
    if (c0 >= c1) return;
    if (bounds_c0 == bounds_c1) bounds_c0 = bounds_c1 = c0;  // nothing covered yet
    const auto fill = [&](int from, int to) {
        // The four bounds share their positions (allocate).
        const std::ptrdiff_t end = u_lo.first + static_cast<std::ptrdiff_t>(u_lo.v.size());
        for (std::ptrdiff_t row = u_lo.first; row < end; row += stride) {
            std::fill(u_lo.at(row + from), u_lo.at(row + to), kNoVelocityBound);
            std::fill(v_lo.at(row + from), v_lo.at(row + to), kNoVelocityBound);
            std::fill(u_hi.at(row + from), u_hi.at(row + to), -kNoVelocityBound);
            std::fill(v_hi.at(row + from), v_hi.at(row + to), -kNoVelocityBound);
        }
    };
    if (c0 < bounds_c0) fill(c0, bounds_c0);
    if (c1 > bounds_c1) fill(bounds_c1, c1);
    bounds_c0 = std::min(bounds_c0, c0);
    bounds_c1 = std::max(bounds_c1, c1);
}

void Stepper::StripBuffers::carry_rows(int by, bool waf, int i0, int i1) {
    // The rows the next strip reads and does not compute, relative to its first row
    // J: the update's 3 x 3 reach (bounds J - 1 .. J + 2 and factors J - 1 .. J, the
    // faces of row J), the neighbours of the rows it computes (velocities and
    // pressure coefficients) and the x-predictor rows under its first y-faces.
    struct Carried {
        StripRows* a;
        int first, count;
    };
    const Carried first_order[] = {
        // clang-format off
        {&su, 1, 4},        {&sv, 1, 4},    {&cx, 1, 2},    {&cy, 1, 2},
        {&ax, 1, 2},        {&ay, 1, 2},
        {&u_lo, -1, 4},     {&u_hi, -1, 4}, {&v_lo, -1, 4}, {&v_hi, -1, 4},
        {&speed_hi, -1, 4}, {&fx_h, 0, 1},  {&fx_hu, 0, 1}, {&fx_hv, 0, 1},
        {&fy_h, 0, 2},      {&fy_hu, 0, 2}, {&fy_hv, 0, 2}, {&factor, -1, 2}};
    // clang-format on
    const Carried predictors[] = {{&yfo_h, 1, 1},  {&yfo_qn, 1, 1},  {&yfo_qt, 1, 1},
                                  {&pred_h, 0, 3}, {&pred_hu, 0, 3}, {&pred_hv, 0, 3},
                                  {&pred_u, 0, 3}, {&pred_v, 0, 3}, {&pred_a, 0, 3}};
    const std::ptrdiff_t first = column0 + i0, width = i1 - i0;
    const auto move = [&](const Carried& c) {
        for (int q = 4 + c.first; q < 4 + c.first + c.count; ++q) {  // row J + d at position 4 + d
            const std::ptrdiff_t to = static_cast<std::ptrdiff_t>(q) * stride + first;
            std::copy_n(c.a->at(to + static_cast<std::ptrdiff_t>(by) * stride), width, c.a->at(to));
        }
    };
    for (const Carried& c : first_order) move(c);
    if (waf)
        for (const Carried& c : predictors) move(c);
}

// ---------------------------------------------------------------- stage 1: per cell

// Pressure coefficients k p of row r in the regime of each cell (w.regime_row, from
// regime_row_into) and the invariant bounds of the update's clamp, columns [ia, ib).
void Stepper::pressure_row(const State& s, int r, int ia, int ib, StripBuffers& w) const {
    const bool metric = terrain_.has_metric;
    const bool isotropic = material_.earth_pressure == EarthPressureModel::isotropic;
    // Inputs and outputs address column 0 of row r.
    const std::ptrdiff_t o = w.k(0, r);
    // The DEM frame stores no px, py, gn: the kernel computes them (and nt) from sx, sy.
    const PressureRowInput in{s.h.row(r),
                              w.su.at(o),
                              w.sv.at(o),
                              metric ? nullptr : terrain_.px.row(r),
                              metric ? nullptr : terrain_.py.row(r),
                              metric ? nullptr : terrain_.gn.row(r),
                              metric ? nullptr : terrain_.normal_thickness.row(r),
                              metric ? terrain_.sx.row(r) : nullptr,
                              metric ? terrain_.sy.row(r) : nullptr,
                              isotropic ? nullptr : w.regime_row.data() + w.column0,
                              terrain_.slope_gravity};
    const PressureRowOutput out{w.cx.at(o),   w.cy.at(o),   w.u_lo.at(o),
                                w.u_hi.at(o), w.v_lo.at(o), w.v_hi.at(o),
                                w.speed_hi.at(o), w.ax.at(o), w.ay.at(o)};
    const PressureRowParams p{k_, k_max_, h_min_, isotropic};
    avalanche::pressure_row(in, out, p, ia, ib);
}

ActiveBox Stepper::per_cell_box(const ActiveBox& b) const {
    const int ng = kGhostLayers;
    return {std::max(b.i0 - ng, -ng), std::min(b.i1 + ng, grid_.nx + ng), std::max(b.j0 - ng, -ng),
            std::min(b.j1 + ng, grid_.ny + ng)};
}

int Stepper::first_new_terms_row(const StripBuffers& w, int r) const {
    return std::max(w.terms_end,
                    std::clamp(r - kRegimeTermsReach, -kGhostLayers, grid_.ny + kGhostLayers - 1));
}

void Stepper::regime_row_into(const State& s, double rest_speed, int r, int ia, int ib,
                              int velocity_end, StripBuffers& w) const {
    const int ng = kGhostLayers, lo = -ng, hi = grid_.nx + ng - 1, top = grid_.ny + ng - 1;
    const auto clamped = [&](int j) { return std::clamp(j, -ng, top); };  // rows, at the padding
    RegimeFlags* row = w.regime_row.data() + w.column0;
    // The row's previous regime, which regime_row replaces cell by cell (regime_ keeps it
    // in another form: stepper.hpp).
    const StoredRegime* kept = regime_.data() + s.h.index(ia, r);
    std::transform(kept, kept + (ib - ia), row + ia, regime_of_stored);
    // The terms of rows r - 2 .. r + 2 (over the columns row r's x-differences read)
    // that the ring does not hold yet. The regime rows of a block of strips come in
    // ascending order, so the ring holds the rest; a new block starts with terms_end at
    // INT_MIN (advect_strip). None of these state rows has been written by a strip yet
    // (advect_strip), so the terms kept are the ones the rows would give now.
    // A row's velocity quotients come with its terms, from the same read of the state
    // rows, when they are the next ones the strip needs (w.vel_end, below
    // velocity_end: advect_strip, step 1); over the terms' columns, which hold the
    // per-cell stage's [ia, ib).
    const int c0 = std::max(ia - 2, lo), c1 = std::min(ib + 2, hi + 1);
    const bool metric = terrain_.has_metric;
    w.terms_end = first_new_terms_row(w, r);
    for (int j = w.terms_end; j <= clamped(r + kRegimeTermsReach); ++j) {
        const bool velocity = j == w.vel_end && j < velocity_end;
        from_line_start(c0, c1, [&](int a, int e) {
            RegimeTermsRow out{w.ring_row(w.term_wet, j), w.ring_row(w.term_still_x, j),
                               w.ring_row(w.term_still_y, j)};
            if (velocity) {
                out.u = w.su.at(w.k(0, j));
                out.v = w.sv.at(w.k(0, j));
            }
            regime_terms_row(s.h.row(j), s.hu.row(j), s.hv.row(j),
                             metric ? terrain_.sx.row(j) : nullptr,
                             metric ? terrain_.sy.row(j) : nullptr, h_min_, rest_speed, out, a, e);
        });
        if (velocity) ++w.vel_end;
    }
    w.terms_end = std::max(w.terms_end, clamped(r + kRegimeTermsReach) + 1);

    const int jm = clamped(r - 1), jp = clamped(r + 1), jmm = clamped(r - 2), jpp = clamped(r + 2);
    RegimeRowInput in{s.h.row(r),    s.hu.row(r), s.hv.row(r),  s.h.row(jm),
                      s.hv.row(jm),  s.h.row(jp), s.hv.row(jp), s.h.row(jmm),
                      s.hv.row(jmm), s.h.row(jpp), s.hv.row(jpp)};
    // The first-order scheme confirms a compression at both scales (regime_rows.cpp says why).
    in.confirm_at_both_scales = numerics_.scheme == Scheme::godunov;
    const auto wet = [&](int j) { return w.ring_row(w.term_wet, j); };
    const auto still_y = [&](int j) { return w.ring_row(w.term_still_y, j); };
    const RegimeRowTerms t{wet(r),     wet(jm),     wet(jp),     wet(jmm),     wet(jpp),
                           w.ring_row(w.term_still_x, r),
                           still_y(r), still_y(jm), still_y(jp), still_y(jmm), still_y(jpp)};
    regime_row_from_terms(in, t, row, ia, ib, lo, hi);
}

void Stepper::keep_regime_row(const State& s, int r, int ia, int ib, StripBuffers& w) {
    // The thread's rows: its block's, and beyond the box's first and last update rows
    // those of the block at that end. Rows of the other blocks it computed are theirs.
    const bool first_block = w.block_j0 == box_.j0, last_block = w.block_j1 == box_.j1;
    if ((!first_block && r < w.block_j0) || (!last_block && r >= w.block_j1)) return;
    const RegimeFlags* row = w.regime_row.data() + w.column0;
    const bool held = (!first_block && r < w.block_j0 + kRegimeHeldRows) ||
                      (!last_block && r >= w.block_j1 - kRegimeHeldRows);
    if (!held) {
        std::transform(row + ia, row + ib, regime_.data() + s.h.index(ia, r), stored_regime);
        return;
    }
    // A segment computes each of its rows' regimes once (its strips carry their rows
    // on), so it holds at most kRegimeHeldRows rows at each inner end; a thread holds
    // those of each of its segments.
    const std::size_t q = w.held_rows.size();
    const std::size_t need = (q + 1) * static_cast<std::size_t>(w.stride);
    if (w.held_regime.size() < need) w.held_regime.resize(need, kRegimeAtStart);
    w.held_rows.push_back(r);
    w.held_cols.emplace_back(ia, ib);
    std::copy_n(row + ia, ib - ia,
                w.held_regime.data() + static_cast<std::ptrdiff_t>(q) * w.stride + w.column0 + ia);
}

// ---------------------------------------------------------------- faces held at rest

// hold_rest_faces_row on face row r of the strip: x-faces (face i between cells i - 1
// and i of row r) or y-faces (face i between cells i of rows r - 1 and r), faces
// [f0, f1); the fluxes address column 0 of the face row.
void Stepper::hold_rest_faces(const State& s, const StripBuffers& w, const HeldFlag* held,
                              bool x_faces, int r, int f0, int f1, double* fh, double* fn,
                              double* ft) const {
    const int rl = x_faces ? r : r - 1, il = x_faces ? -1 : 0;  // the faces' "l" cells
    const std::ptrdiff_t gl = s.h.index(il, rl), gr = s.h.index(0, r);
    const std::ptrdiff_t kl = w.k(il, rl), kr = w.k(0, r);
    // The terrain by its own rows: a chute field stores one (Field2D::same_in_every_row).
    const auto pair = [&](const Field2D& f) { return std::pair{f.row(rl) + il, f.row(r)}; };
    const StripBuffers::StripRows& c = x_faces ? w.cx : w.cy;
    RestFaceRowInput in{s.h.raw().data() + gl, s.h.raw().data() + gr, held + gl, held + gr,
                        c.at(kl), c.at(kr), nullptr, nullptr, nullptr, nullptr,
                        nullptr, nullptr, nullptr, nullptr, nullptr, nullptr};
    if (terrain_.has_metric) {
        // The DEM frame stores no ax, ay, gn: the kernel computes them from the slopes.
        std::tie(in.sn_l, in.sn_r) = pair(x_faces ? terrain_.sx : terrain_.sy);
        std::tie(in.st_l, in.st_r) = pair(x_faces ? terrain_.sy : terrain_.sx);
        in.slope_gravity = terrain_.slope_gravity;
        in.x_faces = x_faces;
    } else {
        std::tie(in.an_l, in.an_r) = pair(x_faces ? terrain_.ax : terrain_.ay);
        std::tie(in.at_l, in.at_r) = pair(x_faces ? terrain_.ay : terrain_.ax);
        std::tie(in.gn_l, in.gn_r) = pair(terrain_.gn);
    }
    const RestFaceRowParams p{1.0 / (x_faces ? grid_.dx : grid_.dy), tan_delta_, h_min_};
    hold_rest_faces_row(in, p, fh, fn, ft, f0, f1);
}

// ---------------------------------------------------------------- one strip

void Stepper::advect_strip(State& s, double tau, const ActiveBox& b, int J, int Je,
                           StripBuffers& w, int wait_first, int wait_last) {
    const int ng = kGhostLayers, nx = grid_.nx, ny = grid_.ny;
    const bool waf = numerics_.scheme == Scheme::waf;
    const double hd = h_min_;
    const std::ptrdiff_t st = s.h.stride();
    // Columns of the per-cell stage and the y-predictor: every column a stage uses.
    const ActiveBox per_cell = per_cell_box(b);
    const int pc0 = per_cell.i0, pc1 = per_cell.i1;
    // The thread's previous strip ended at J: the stage rows this strip reads and that
    // one computed are moved to their places in the buffers (carry_rows), and only the
    // rest is computed below. Otherwise every stage starts empty.
    if (w.carried_for == J) {
        w.carry_rows(J - 4 - w.base, waf, pc0, pc1);
    } else {
        w.vel_end = w.p_end = w.yfo_end = w.xf_end = w.xp_end = w.yf_end = w.fac_end =
            w.terms_end = std::numeric_limits<int>::min();
    }
    w.base = J - 4;

    // Row ranges [lo, hi) of the stages: the whole-box ranges of the operator, cut to
    // what the update of rows [J, Je) reads.
    const int pr0 = per_cell.j0, pr1 = per_cell.j1;  // per-cell stage
    const int x0 = std::max(J - 1, b.j0), x1 = std::min(Je + 1, b.j1);  // x-faces (and y-predictor)
    const int y0 = std::max(J - 1, b.j0), y1 = std::min(Je + 2, b.j1 + 1);  // y-faces
    const int xp0 = std::max(y0 - 2, pr0), xp1 = std::min(y1 + 1, pr1);     // x-predictor
    const int q0 = std::max(std::min({J - 1, x0 - 1, y0 - 1, xp0}), pr0);
    const int q1 = std::min(std::max({Je + 1, x1 + 1, y1, xp1}), pr1);
    const bool regimes = material_.earth_pressure != EarthPressureModel::isotropic;
    // The velocity quotients' rows (step 1).
    const int v0 = std::max(J - 4, -ng), v1 = std::min(Je + (regimes ? 5 : 4), ny + ng);

    // The rows beyond [J, Je) that these ranges read of the state: the velocity
    // quotients', the regime terms' of the pressure rows, the first-order faces' (rows
    // r - 1 and r of face row r: the y-faces y0 .. y1 - 1, and the y-predictor's
    // x0 .. x1, the same rows; the donor factors and rest faces read within them); and
    // the rows whose regimes this strip computes. A neighbouring segment's first or last
    // strip holds back that many of its rows (kStateRowsReadBeyond, kRegimeHeldRows):
    // the tests check them against the most recorded here.
    const int terms = regimes ? kRegimeTermsReach : 0;
    w.rows_read_beyond = std::max({w.rows_read_beyond, J - v0, v1 - Je, J - (q0 - terms),
                                   q1 + terms - Je, J - (y0 - 1), y1 - Je});
    if (regimes) w.regime_rows_beyond = std::max({w.regime_rows_beyond, J - q0, q1 - Je});

    // 1. The velocity quotients of the state, once per cell, rows v0 .. v1 - 1: for the
    // pressure stage (rows q0 .. q1 - 1) and the first-order fluxes on the state (faces
    // reading rows J - 3 .. Je + 2), and rows Je + 3 and, with regimes, Je + 4 for the
    // segment's next strip (carry_rows; without regimes that strip computes row Je + 4
    // over what is carried). Row J - 4 is read by none of them (with v0 = J - 3 the 18
    // bench_equivalence hashes were unchanged, 2026-12-06; not kept: it would save only
    // one row at a segment's start). With regimes each row's come with its regime terms
    // (regime_row_into), which reach row Je + 4 here, from the same read of the state
    // (1.2 % of case (a)'s WAF run, docs/performance.md); the rows those do not cover are
    // computed on their own, before the regime rows (none, but for a segment's first
    // rows near the grid's bottom) and after them (at the box's top). Then the pressure
    // coefficients and invariant bounds.
    const auto velocity_rows_until = [&](int end) {
        for (; w.vel_end < end; ++w.vel_end) {
            const int r = w.vel_end;
            const std::ptrdiff_t k = w.k(0, r);
            from_line_start(pc0, pc1, [&](int ia, int ib) {
                state_velocity_row(s.h.row(r), s.hu.row(r), s.hv.row(r), w.su.at(k), w.sv.at(k), ia,
                                   ib);
            });
        }
    };
    w.vel_end = std::max(w.vel_end, v0);
    const int p_first = std::max(q0, w.p_end);
    // The first row whose terms regime_row_into computes (if it runs: p_first < q1).
    const int terms_first = regimes && p_first < q1 ? first_new_terms_row(w, p_first) : v1;
    velocity_rows_until(std::min(terms_first, v1));

    // The regime of each pressure row first (regime_row_into): its previous regime and
    // the state's rows r - 2 .. r + 2, none of which a strip has written yet.
    const double rest_speed = 0.5 * tan_delta_ * numerics_.gravity * tau;  // see regime_row
    for (int r = p_first; r < q1; ++r) {
        if (regimes) {
            regime_row_into(s, rest_speed, r, pc0, pc1, v1, w);
            keep_regime_row(s, r, pc0, pc1, w);
        }
        from_line_start(pc0, pc1, [&](int ia, int ib) { pressure_row(s, r, ia, ib, w); });
    }
    w.p_end = std::max(w.p_end, q1);
    velocity_rows_until(v1);

    const double* sh = s.h.raw().data();
    const double* shu = s.hu.raw().data();
    const double* shv = s.hv.raw().data();
    const auto full = [&](int i, int r) { return s.h.index(i, r); };
    // c: the pressure coefficients, a: the celerities (both from buffer index kc).
    const auto face_in = [&](const double* h, const double* qn, const double* qt, std::ptrdiff_t kq,
                             const StripBuffers::StripRows& c, const StripBuffers::StripRows& a,
                             std::ptrdiff_t kc, std::ptrdiff_t off) {
        FaceRowInput in{h + kq, qn + kq, qt + kq, c.at(kc), off};
        in.a = a.at(kc);
        return in;
    };
    // The same with the state's velocity quotients (normal un, tangential ut) from buffer index kv.
    const auto with_velocities = [](FaceRowInput in, const StripBuffers::StripRows& un,
                                    const StripBuffers::StripRows& ut, std::ptrdiff_t kv) {
        in.un = un.at(kv);
        in.ut = ut.at(kv);
        return in;
    };
    const auto face_out = [](StripBuffers::StripRows& a, StripBuffers::StripRows& b2,
                             StripBuffers::StripRows& c, std::ptrdiff_t k) {
        return FaceRowOutput{a.at(k), b2.at(k), c.at(k)};
    };
    const double dt_dx = tau / grid_.dx, dt_dy = tau / grid_.dy;
    const Limiter lim = numerics_.limiter;

    // Walls pass no mass and no tangential momentum; open edges pass only outflow.
    const bool wall = numerics_.boundary == Boundary::wall;
    const auto fix = [&](double& fh, double& fn, double& ft, double outward_sign, int ii, int jj,
                         double c) {
        if (wall || fh * outward_sign < 0.0) {
            // Wall flux: keep the normal momentum (pressure and reflection), no mass.
            fh = 0.0;
            ft = 0.0;
            if (!wall) {
                // Inflow at an open edge is refused; the interior's pressure acts as at a wall.
                const double h = s.h(ii, jj) >= h_min_ ? s.h(ii, jj) : 0.0;
                fn = 0.5 * c * h * h;
            }
        }
    };
    const auto fix_x_faces = [&](int r) {
        if (b.i0 == 0) {
            const std::ptrdiff_t k = w.k(0, r);
            fix(w.fx_h[k], w.fx_hu[k], w.fx_hv[k], -1.0, 0, r, w.cx[k]);
        }
        if (b.i1 == nx) {
            const std::ptrdiff_t k = w.k(nx, r);
            fix(w.fx_h[k], w.fx_hu[k], w.fx_hv[k], 1.0, nx - 1, r, w.cx[w.k(nx - 1, r)]);
        }
    };
    const auto fix_y_faces = [&](int r) {  // the face rows on the south and north edges
        if (r != 0 && r != ny) return;
        const int jj = r == 0 ? 0 : ny - 1;
        for (int i = b.i0; i < b.i1; ++i) {
            const std::ptrdiff_t k = w.k(i, r);
            fix(w.fy_h[k], w.fy_hv[k], w.fy_hu[k], r == 0 ? -1.0 : 1.0, i, jj, w.cy[w.k(i, jj)]);
        }
    };

    // Faces friction holds at rest (numerics.rest_faces, rest_faces.hpp): before the
    // edges' own rules, which override them.
    const auto hold_x_faces = [&](int r) {
        if (rest_in_ == nullptr) return;
        const std::ptrdiff_t k = w.k(0, r);
        hold_rest_faces(s, w, rest_in_, true, r, b.i0, b.i1 + 1, w.fx_h.at(k),
                        w.fx_hu.at(k), w.fx_hv.at(k));
    };
    const auto hold_y_faces = [&](int r) {
        if (rest_in_ == nullptr) return;
        const std::ptrdiff_t k = w.k(0, r);
        hold_rest_faces(s, w, rest_in_, false, r, b.i0, b.i1, w.fy_h.at(k),
                        w.fy_hv.at(k), w.fy_hu.at(k));
    };

    // 2. x-faces: WAF on the state advanced tau/2 in y (Wang & Li 2017 eqs. 6-9), or
    // first-order HLLC on the state.
    if (waf) {
        const double ratio = 0.5 * tau / grid_.dy;
        // The state's y-faces and the y-predictor over the columns [ia, ib).
        const auto y_state = [&](int ia, int r) {
            return with_velocities(face_in(sh, shv, shu, full(ia, r), w.cy, w.ay, w.k(ia, r), st),
                                   w.sv, w.su, w.k(ia, r));
        };
        for (int r = std::max(x0, w.yfo_end); r <= x1;
             ++r)  // first-order y-faces r (rows r - 1 | r)
            from_line_start(pc0, pc1, [&](int ia, int ib) {
                hllc_face_row(y_state(ia, r), face_out(w.yfo_h, w.yfo_qn, w.yfo_qt, w.k(ia, r)),
                              ib - ia, hd);
            });
        w.yfo_end = std::max(w.yfo_end, x1 + 1);
        for (int r = std::max(x0, w.xf_end); r < x1; ++r) {
            // The y-predictor of row r, used at once by the x-faces of row r.
            // Its velocity quotients (normal hv / h, tangential hu / h) are kept for the
            // x-faces, which read every cell twice.
            from_line_start(pc0, pc1, [&](int ia, int ib) {
                const std::ptrdiff_t c = w.column0 + ia;
                FaceRowOutput predicted{w.row_h.data() + c, w.row_hv.data() + c,
                                        w.row_hu.data() + c};
                predicted.un = w.row_v.data() + c;
                predicted.ut = w.row_u.data() + c;
                predictor_row(y_state(ia, r), face_out(w.yfo_h, w.yfo_qn, w.yfo_qt, w.k(ia, r)),
                              ratio, hd, predicted, ib - ia);
                celerity_row(w.row_h.data() + c, w.cx.at(w.k(ia, r)), hd, w.row_a.data() + c,
                             ib - ia);
            });
            const std::ptrdiff_t k = w.k(b.i0, r), c0 = w.column0 + b.i0;
            FaceRowInput in{w.row_h.data() + c0, w.row_hu.data() + c0, w.row_hv.data() + c0,
                            w.cx.at(k), 1};
            in.un = w.row_u.data() + c0;
            in.ut = w.row_v.data() + c0;
            in.a = w.row_a.data() + c0;
            waf_face_row(in, face_out(w.fx_h, w.fx_hu, w.fx_hv, k), b.i1 + 1 - b.i0, hd, dt_dx,
                         lim);
            hold_x_faces(r);
            fix_x_faces(r);
        }
    } else {
        for (int r = std::max(x0, w.xf_end); r < x1; ++r) {
            hllc_face_row(
                with_velocities(face_in(sh, shu, shv, full(b.i0, r), w.cx, w.ax, w.k(b.i0, r), 1),
                                w.su, w.sv, w.k(b.i0, r)),
                face_out(w.fx_h, w.fx_hu, w.fx_hv, w.k(b.i0, r)), b.i1 + 1 - b.i0, hd);
            hold_x_faces(r);
            fix_x_faces(r);
        }
    }
    w.xf_end = std::max(w.xf_end, x1);

    // 3. y-faces: WAF on the state advanced tau/2 in x, or first-order HLLC.
    if (waf) {
        const double ratio = 0.5 * tau / grid_.dx;
        const int n = b.i1 - b.i0;
        for (int r = std::max(xp0, w.xp_end); r < xp1; ++r) {
            const std::ptrdiff_t c0 = w.column0 + b.i0;
            const FaceRowOutput first_order{w.row_h.data() + c0, w.row_hu.data() + c0,
                                            w.row_hv.data() + c0};
            hllc_face_row(
                with_velocities(face_in(sh, shu, shv, full(b.i0, r), w.cx, w.ax, w.k(b.i0, r), 1),
                                w.su, w.sv, w.k(b.i0, r)),
                first_order, n + 1, hd);
            FaceRowOutput predicted = face_out(w.pred_h, w.pred_hu, w.pred_hv, w.k(b.i0, r));
            predicted.un = w.pred_u.at(w.k(b.i0, r));
            predicted.ut = w.pred_v.at(w.k(b.i0, r));
            predictor_row(
                with_velocities(face_in(sh, shu, shv, full(b.i0, r), w.cx, w.ax, w.k(b.i0, r), 1),
                                w.su, w.sv, w.k(b.i0, r)),
                first_order, ratio, hd, predicted, n);
            celerity_row(w.pred_h.at(w.k(b.i0, r)), w.cy.at(w.k(b.i0, r)), hd,
                         w.pred_a.at(w.k(b.i0, r)), n);
        }
        w.xp_end = std::max(w.xp_end, xp1);
        for (int r = std::max(y0, w.yf_end); r < y1; ++r) {
            const std::ptrdiff_t k = w.k(b.i0, r);
            waf_face_row(with_velocities(face_in(w.pred_h.at(k), w.pred_hv.at(k),
                                                 w.pred_hu.at(k), 0, w.cy, w.pred_a, k, st),
                                         w.pred_v, w.pred_u, k),
                         face_out(w.fy_h, w.fy_hv, w.fy_hu, k), n, hd, dt_dy, lim);
            hold_y_faces(r);
            fix_y_faces(r);
        }
    } else {
        for (int r = std::max(y0, w.yf_end); r < y1; ++r) {
            hllc_face_row(
                with_velocities(face_in(sh, shv, shu, full(b.i0, r), w.cy, w.ay, w.k(b.i0, r), st),
                                w.sv, w.su, w.k(b.i0, r)),
                face_out(w.fy_h, w.fy_hv, w.fy_hu, w.k(b.i0, r)), b.i1 - b.i0, hd);
            hold_y_faces(r);
            fix_y_faces(r);
        }
    }
    w.yf_end = std::max(w.yf_end, y1);

    // 4. Donor factors (positivity and the thin-layer rule, conservatively): each face
    // flux is scaled by the factor of its donor cell (the cell its mass leaves), chosen
    // so that no cell exports more than it holds; thin cells (h < h_min) export
    // nothing. Faces reach one cell beyond the box; that ring is dry, so its faces
    // carry no mass, but it is set to 1 so that no stale value can ever scale a flux.
    const double rx = tau / grid_.dx, ry = tau / grid_.dy;
    const auto rows_at = [&w](std::ptrdiff_t kw) {  // the face fluxes from buffer index kw
        return FaceFluxRows{w.fx_h.at(kw), w.fx_hu.at(kw), w.fx_hv.at(kw),
                            w.fy_h.at(kw), w.fy_hu.at(kw), w.fy_hv.at(kw)};
    };
    StripBuffers::StripRows& factor = w.factor;
    for (int r = std::max(J - 1, w.fac_end); r <= Je; ++r) {
        if (r < b.j0 || r >= b.j1) {
            for (int i = b.i0 - 1; i <= b.i1; ++i) factor[w.k(i, r)] = 1.0;
            continue;
        }
        factor[w.k(b.i0 - 1, r)] = factor[w.k(b.i1, r)] = 1.0;
        const std::ptrdiff_t kw = w.k(0, r);
        donor_factor_row(rows_at(kw), sh + full(0, r), rx, ry, hd, st, factor.at(kw), b.i0, b.i1);
    }
    w.fac_end = std::max(w.fac_end, Je + 1);

    // 5. Conservative update, U -= tau/dx dF + tau/dy dG (Wang & Li 2017 eq. 5), with
    // the scaled fluxes. Every stage above is done with rows [J, Je) of s, and the
    // thread's next strip reads none of them (it reads the stage rows it is handed), so
    // they are updated in place (a cell's update reads only its own state), unless
    // another thread's strip reads them (advect(): the wait_first and wait_last rows at
    // the strip's ends): then into the strip's out rows, which step 7 moves on. Each
    // face is scaled by its donor's factor where it is used, so both cells of a face
    // compute the same product (x * 1 == x exactly for the unscaled faces). A zero mass
    // flux has no donor: its momentum (the pressure of a wall face) passes unscaled.
    const bool metric = terrain_.has_metric;
    const UpdateRowParams up{rx, ry, st, energy_budget_, numerics_.gravity, h_min_};
    const int first_end = std::min(J + wait_first, Je), last_begin = std::max(Je - wait_last, J);
    for (int r = J; r < Je; ++r) {
        const bool wait = r < first_end || r >= last_begin;
        const std::ptrdiff_t kw = w.k(0, r), kf = full(0, r);
        const UpdateRowInput in{rows_at(kw),
                                factor.at(kw),
                                w.u_lo.at(kw),
                                w.u_hi.at(kw),
                                w.v_lo.at(kw),
                                w.v_hi.at(kw),
                                w.speed_hi.at(kw),
                                sh + kf,
                                shu + kf,
                                shv + kf,
                                terrain_.elevation.row(r),
                                metric ? terrain_.sx.row(r) : nullptr,
                                metric ? terrain_.sy.row(r) : nullptr};
        double* h_new = wait ? w.out_h.at(kw) : s.h.row(r);
        double* hu_new = wait ? w.out_hu.at(kw) : s.hu.row(r);
        double* hv_new = wait ? w.out_hv.at(kw) : s.hv.row(r);
        update_row(in, up, h_new, hu_new, hv_new, b.i0, b.i1);
        if (rest_in_ != nullptr)
            keep_held_at_rest(rest_in_ + kf, w.fx_h.at(kw), w.fy_h.at(kw), w.stride, hu_new, hv_new,
                              rest_out_ ? rest_out_ + kf : nullptr, b.i0, b.i1);
        // The next step's CFL rate of the row, while it is in the cache (a pass of its
        // own read the state from memory again); a waiting row's once it is in s.
        if (take_cfl_rate_ && !wait)
            w.cfl_rate = std::max(w.cfl_rate, cfl_rate_of_row(s, r, b.i0, b.i1));
    }

    // 6. Volume through the open edges, after scaling, per boundary face (summed in
    // advect() in a fixed order).
    const auto outflow = [&](const StripBuffers::StripRows& fh, std::ptrdiff_t k, std::ptrdiff_t off,
                             double sign) {
        return std::max(sign * (fh[k] * donor_factor_of(fh[k], factor[k - off], factor[k])), 0.0);
    };
    for (int r = J; r < Je; ++r) {
        if (b.i0 == 0) edge_outflow_[0][r] = outflow(w.fx_h, w.k(0, r), 1, -1.0) * tau * grid_.dy;
        if (b.i1 == nx) edge_outflow_[1][r] = outflow(w.fx_h, w.k(nx, r), 1, 1.0) * tau * grid_.dy;
    }
    if (b.j0 == 0 && J == 0)
        for (int i = b.i0; i < b.i1; ++i)
            edge_outflow_[2][i] = outflow(w.fy_h, w.k(i, 0), st, -1.0) * tau * grid_.dx;
    if (b.j1 == ny && Je == ny)
        for (int i = b.i0; i < b.i1; ++i)
            edge_outflow_[3][i] = outflow(w.fy_h, w.k(i, ny), st, 1.0) * tau * grid_.dx;
    w.carried_for = Je;

    // 7. The rows another thread's strip reads wait in the thread's waiting rows until
    // every segment is done (advect()), one entry per run of rows.
    const auto keep = [&](int j0, int j1) {
        if (j0 >= j1) return;
        if (static_cast<int>(w.waiting.size()) <= w.waiting_used) w.waiting.emplace_back();
        StripBuffers::WaitingRows& wr = w.waiting[static_cast<std::size_t>(w.waiting_used++)];
        wr.j0 = j0;
        wr.j1 = j1;
        wr.i0 = b.i0;
        wr.i1 = b.i1;
        const std::size_t width = static_cast<std::size_t>(b.i1 - b.i0);
        const std::size_t n = width * static_cast<std::size_t>(j1 - j0);
        for (auto* a : {&wr.h, &wr.hu, &wr.hv})
            if (a->size() < n) a->resize(n);
        for (int r = j0; r < j1; ++r) {
            const std::ptrdiff_t kw = w.k(b.i0, r);
            const std::ptrdiff_t kt = wr.at(b.i0, r);
            std::copy_n(w.out_h.at(kw), width, wr.h.data() + kt);
            std::copy_n(w.out_hu.at(kw), width, wr.hu.data() + kt);
            std::copy_n(w.out_hv.at(kw), width, wr.hv.data() + kt);
        }
    };
    if (first_end >= last_begin) {
        keep(J, Je);  // the two runs meet (or one is the whole strip)
    } else {
        keep(J, first_end);
        keep(last_begin, Je);
    }
}

// ---------------------------------------------------------------- the operator

void Stepper::advect(State& s, double tau) {
    fill_ghosts_near(s, box_);
    const ActiveBox b = box_;
    if (b.empty()) {
        thin_layer_velocities(s);
        films_settled_ = true;
        return;
    }
    const int threads = threaded_ ? omp_get_max_threads() : 1;
    if (static_cast<int>(strips_.size()) < threads)
        strips_.resize(static_cast<std::size_t>(threads));
    for (int t = 0; t < threads; ++t) {
        StripBuffers& w = strips_[static_cast<std::size_t>(t)];
        if (w.rows == 0)
            w.allocate(s.h.stride(), s.h.column0(), kStripRows, numerics_.scheme == Scheme::waf);
        w.carried_for = std::numeric_limits<int>::min();  // a new state: nothing carries over
    }
    for (StripBuffers& w : strips_) w.cfl_rate = 0.0;
    // The regimes are computed row by row with the pressure stage (advect_strip) and
    // replace the previous ones in regime_ as they go, but for the rows near a segment's
    // inner ends, which the neighbouring segment also computes from the previous ones.
    if (regime_.size() != s.h.raw().size())
        regime_ = CellVector<StoredRegime>(s.h.raw().size());  // at start
    // The flags of the faces friction holds (rest_faces.hpp): after the friction stage
    // those it set; otherwise (the first advection of an L S L step) those of its cells
    // that the advection after it left quiet.
    rest_in_ = nullptr;
    rest_out_ = nullptr;
    if (numerics_.rest_faces) {
        const std::size_t n = s.h.raw().size();
        if (after_sources_) {
            if (held_.size() == n) rest_in_ = held_.data();
            if (numerics_.splitting == Splitting::lsl) {
                if (held_quiet_.size() != n) held_quiet_ = CellVector<HeldFlag>(n);
                rest_out_ = held_quiet_.data();
            }
        } else {
            // Before any friction stage (the first advection of an L S L run): the cells at
            // rest, as the friction stage would hold them where the faces' test passes.
            // Only the box's: it holds every wet cell, and the state beyond it is left
            // unread (on a large DEM its pages stay unmade, field_storage.hpp).
            if (held_quiet_.size() != n) {
                held_quiet_ = CellVector<HeldFlag>(n);
                for (int j = b.j0; j < b.j1; ++j)
                    held_at_rest_row(s.h.row(j), s.hu.row(j), s.hv.row(j), h_min_,
                                     held_quiet_.data() + s.h.index(0, j), b.i0, b.i1);
            }
            rest_in_ = held_quiet_.data();
        }
        after_sources_ = false;
    }
    const bool regimes = material_.earth_pressure != EarthPressureModel::isotropic;
    const bool waf = numerics_.scheme == Scheme::waf;

    // The strips of the bands (make_bands) in row order, and the cells before each.
    struct Strip {
        std::size_t band;
        int j0, j1;
    };
    std::vector<Strip> strips;
    std::vector<std::size_t> cells_before{0};
    for (std::size_t q = 0; q < bands_.size(); ++q) {
        const ActiveBox& band = bands_[q];
        if (band.empty()) continue;
        // Bands' heights are multiples of kStripRows, so of every height strip_rows_for
        // chooses: only the box's last strip is shorter.
        const int rows = fixed_strip_rows_ > 0
                             ? fixed_strip_rows_
                             : strip_rows_for(band.i1 - band.i0 + 2 * kGhostLayers, waf);
        for (int j = band.j0; j < band.j1; j += rows) {
            strips.push_back({q, j, std::min(j + rows, band.j1)});
            cells_before.push_back(cells_before.back() + static_cast<std::size_t>(band.i1 - band.i0) *
                                                             static_cast<std::size_t>(strips.back().j1 - j));
        }
    }
    const int nstrips = static_cast<int>(strips.size());
    // Each strip's band's last strip; and the strips reserved to the thread after each
    // strip it claims (StripClaims): enough to span kRowsKnownAhead rows, so that a
    // strip knows its segment's end wherever its rows must hold anything back for it
    // (advect_strip). fewest_rows: the lowest strip but the box's last, which no strip
    // follows.
    std::vector<int> band_last(strips.size());
    int fewest_rows = kStripRows;
    for (int q = nstrips - 1; q >= 0; --q) {
        const Strip& st = strips[static_cast<std::size_t>(q)];
        const bool last_of_band =
            q + 1 == nstrips || strips[static_cast<std::size_t>(q + 1)].band != st.band;
        band_last[static_cast<std::size_t>(q)] =
            last_of_band ? q : band_last[static_cast<std::size_t>(q + 1)];
        if (q + 1 < nstrips) fewest_rows = std::min(fewest_rows, st.j1 - st.j0);
    }
    const int reserved = (kRowsKnownAhead + fewest_rows - 1) / fewest_rows;
    // Thread t of n starts on the strips from the strip boundary nearest to t / n of the
    // cells (share_start): a whole avaKot run at 5 m on two threads spent 7.0-7.5 s in
    // its time loop with the first boundary at or beyond, 6.5-6.9 s now. Cutting the
    // strip at the share into two (shares even to a row) once changed the run's maps in
    // the last bits: a segment's first or last strip then held back at most its own
    // rows, too few where it was shorter than kStateRowsReadBeyond (strips of 3 rows
    // changed bench_equivalence's hashes the same way). The rows held back now span
    // strips (kRowsKnownAhead below), so such a cut would keep the bits; it has not been
    // tried again. A thread whose share is done takes half of
    // what another has left (StripClaims): the cores of this VM run at different speeds.
    // (Weighting the strips by their cost per cell, timed at the last advection, gained
    // nothing on the avaKot run.)
    // The edge faces' outflow of the rows and columns no band reaches is zero.
    const int nx = grid_.nx, ny = grid_.ny;
    if (b.i0 == 0) std::fill(edge_outflow_[0].begin() + b.j0, edge_outflow_[0].begin() + b.j1, 0.0);
    if (b.i1 == nx) std::fill(edge_outflow_[1].begin() + b.j0, edge_outflow_[1].begin() + b.j1, 0.0);
    if (b.j0 == 0) std::fill(edge_outflow_[2].begin() + b.i0, edge_outflow_[2].begin() + b.i1, 0.0);
    if (b.j1 == ny) std::fill(edge_outflow_[3].begin() + b.i0, edge_outflow_[3].begin() + b.i1, 0.0);

    // Each thread claims strips in row order; its consecutive strips of one band are a
    // segment, whose strips hand their stage rows on (advect_strip) and whose first strip
    // computes them afresh. A segment's first and last strips share rows with the
    // neighbouring segments, whose strips read the old state there: those updated rows
    // (kStateRowsReadBeyond at each inner end) wait in the thread's buffers until every
    // segment is done. The other rows go into s at once (advect_strip, steps 5 and 7),
    // so no second state is kept.
    StripClaims claims;
    const ActiveBox per_cell = per_cell_box(b);
#pragma omp parallel if (threaded_)
    {
        const int n = omp_get_num_threads(), t = omp_get_thread_num();
#pragma omp single
        {
            std::vector<int> first(static_cast<std::size_t>(n) + 1);
            for (int q = 0; q <= n; ++q) {
                const int all_first = q == 0 ? 0 : nstrips;  // set_all_strips_to_first_thread
                first[static_cast<std::size_t>(q)] =
                    all_strips_to_first_thread_ ? all_first : share_start(cells_before, q, n);
            }
            claims.reset(first, all_strips_to_first_thread_, reserved);  // the others claim first
        }
        StripBuffers& w = strips_[static_cast<std::size_t>(t)];
        // The columns the stages read of the bounds: the per-cell stage's, with a
        // margin (buffer positions: column -ng at 0).
        w.cover_columns(w.column0 + per_cell.i0 - 2, w.column0 + per_cell.i1 + 2);
        w.waiting_used = 0;
        w.held_rows.clear();
        w.held_cols.clear();
        const auto band_of = [&](int q) { return strips[static_cast<std::size_t>(q)].band; };
        for (StripClaims::Claim c = claims.next(t); c.strip >= 0; c = claims.next(t)) {
            const int k = c.strip;
            const Strip& st = strips[static_cast<std::size_t>(k)];
            const bool starts = c.starts || k == 0 || band_of(k - 1) != st.band;
            if (starts) {
                w.carried_for = std::numeric_limits<int>::min();  // a new segment
                w.block_j0 = st.j0;
            }
            // The segment's last strip: its share's or its band's, whichever comes first,
            // known where it is among the strips reserved after this one (StripClaims).
            const int band_end = band_last[static_cast<std::size_t>(k)];
            const int share_end =
                c.share_last >= 0 ? c.share_last : std::numeric_limits<int>::max();
            const int last = std::min(band_end, share_end);
            const bool last_known = last <= k + reserved;
            // The segment's end as far as this strip's regime rows need it
            // (keep_regime_row): where it is not known it is at or beyond the end of the
            // reserved strips, kRowsKnownAhead rows or more past this strip's end, farther
            // than the regime rows this strip computes (two past its end at most) and
            // those held before an end (kRegimeHeldRows), and this strip's rows hold
            // nothing back there.
            const int end_strip = last_known ? last : k + reserved;
            w.block_j1 = strips[static_cast<std::size_t>(end_strip)].j1;
            // The rows the strips of the neighbouring segments read wait (advect_strip):
            // the segment's first and last kStateRowsReadBeyond rows, which span several
            // strips where strips are shorter.
            // (A segment that starts at the first strip has no neighbour before it.)
            const int rows = st.j1 - st.j0;
            const bool holds_first = w.block_j0 != strips.front().j0;
            const int wait_first =
                holds_first ? std::clamp(w.block_j0 + kStateRowsReadBeyond - st.j0, 0, rows) : 0;
            const int wait_last =
                last_known && last + 1 < nstrips
                    ? std::clamp(st.j1 - (w.block_j1 - kStateRowsReadBeyond), 0, rows)
                    : 0;
            // The band's columns; its stages' row ranges are the box's (advect_strip).
            const ActiveBox& band = bands_[st.band];
            advect_strip(s, tau, ActiveBox{band.i0, band.i1, b.j0, b.j1}, st.j0, st.j1, w,
                         wait_first, wait_last);
        }
        // Every segment done: each thread now stores the regimes and rows its own
        // segments held back (rows of one thread only, so the threads write apart).
#pragma omp barrier
        for (std::size_t q = 0; q < w.held_rows.size(); ++q) {
            const auto [c0, c1] = w.held_cols[q];
            const RegimeFlags* held =
                w.held_regime.data() + static_cast<std::ptrdiff_t>(q) * w.stride + w.column0 + c0;
            std::transform(held, held + (c1 - c0), regime_.data() + s.h.index(c0, w.held_rows[q]),
                           stored_regime);
        }
        for (int q = 0; q < w.waiting_used; ++q) {
            const StripBuffers::WaitingRows& wr = w.waiting[static_cast<std::size_t>(q)];
            const std::size_t width = static_cast<std::size_t>(wr.i1 - wr.i0);
            for (int j = wr.j0; j < wr.j1; ++j) {
                const std::ptrdiff_t k = wr.at(wr.i0, j);
                std::copy_n(wr.h.data() + k, width, s.h.row(j) + wr.i0);
                std::copy_n(wr.hu.data() + k, width, s.hu.row(j) + wr.i0);
                std::copy_n(wr.hv.data() + k, width, s.hv.row(j) + wr.i0);
                if (take_cfl_rate_)
                    w.cfl_rate = std::max(w.cfl_rate, cfl_rate_of_row(s, j, wr.i0, wr.i1));
            }
        }
    }
    strip_steals_ += static_cast<std::uint64_t>(claims.steals());
    if (take_cfl_rate_) {
        double rate = 0.0;
        for (const StripBuffers& w : strips_) rate = std::max(rate, w.cfl_rate);
        dt_of_last_step_ = dt_of_rate(rate);
    }
    for (const StripBuffers& w : strips_) {
        state_rows_read_beyond_ = std::max(state_rows_read_beyond_, w.rows_read_beyond);
        regime_rows_beyond_ = std::max(regime_rows_beyond_, w.regime_rows_beyond);
    }
    // Volume through the open edges: west, east, south, north, in that order.
    double out = 0.0;
    if (b.i0 == 0)
        for (int j = b.j0; j < b.j1; ++j) out += edge_outflow_[0][j];
    if (b.i1 == grid_.nx)
        for (int j = b.j0; j < b.j1; ++j) out += edge_outflow_[1][j];
    if (b.j0 == 0)
        for (int i = b.i0; i < b.i1; ++i) out += edge_outflow_[2][i];
    if (b.j1 == grid_.ny)
        for (int i = b.i0; i < b.i1; ++i) out += edge_outflow_[3][i];
    outflow_volume_ += out;
    // The whole box would have given every empty cell of its per-cell stage the regime
    // at start (regime_row); the bands computed those of their own rows and columns.
    if (regimes && !(bands_.size() == 1 && bands_.front() == b)) {
        const ActiveBox& pc = per_cell;
        const StoredRegime at_start = stored_regime(kRegimeAtStart);
        std::size_t q = 0;  // the band that stores row r's regimes (keep_regime_row)
        for (int r = pc.j0; r < pc.j1; ++r) {
            while (q + 1 < bands_.size() && r >= bands_[q].j1) ++q;
            StoredRegime* row = regime_.data() + s.h.index(0, r);
            if (bands_[q].empty()) {
                std::fill(row + pc.i0, row + pc.i1, at_start);
                continue;
            }
            const ActiveBox own = per_cell_box(bands_[q]);
            std::fill(row + pc.i0, row + own.i0, at_start);
            std::fill(row + own.i1, row + pc.i1, at_start);
        }
    }
    fill_ghosts_near(s, box_);
    thin_layer_velocities(s);
    films_settled_ = true;  // every film of the bands without a wet neighbour at rest
}

}  // namespace avalanche
