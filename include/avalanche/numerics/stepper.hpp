#pragma once
// One time step of the Savage–Hutter solver: Strang splitting of advection L and
// point-wise sources S (Wang & Li 2017 eq. 12), with
//  - L: unsplit WAF-TVD fluxes on states advanced half a step by a transverse
//    first-order Godunov predictor (eqs. 6-9), or the first-order HLLC Godunov flux;
//  - the thin-layer wet/dry rule (section 2.2.3): cells thinner than h_min do not
//    export mass, take the velocity of their deepest wet neighbour, or stop;
//  - a conservative positivity limiter that scales the outgoing face fluxes of a
//    cell that would otherwise be emptied below zero;
//  - S: tangential gravity, then Coulomb friction as a stopping magnitude;
//  - an energy cap: no cell is faster than a frictionless point mass falling from
//    the highest free surface of the state the run started from, plus that state's
//    kinetic and pressure energy (docs/numerics.md, "Energy cap").
// The state's ghost cells are filled here from the boundary conditions.
#include <array>
#include <cstdint>
#include <optional>
#include <utility>
#include <vector>

#include "avalanche/core/field_storage.hpp"
#include "avalanche/core/grid.hpp"
#include "avalanche/core/state.hpp"
#include "avalanche/numerics/active_box.hpp"
#include "avalanche/numerics/cell_rows.hpp"
#include "avalanche/numerics/parameters.hpp"
#include "avalanche/numerics/rest_faces.hpp"
#include "avalanche/physics/earth_pressure.hpp"
#include "avalanche/physics/material.hpp"
#include "avalanche/physics/terrain.hpp"

namespace avalanche {

class Stepper {
  public:
    Stepper(const Grid& grid, const TerrainFields& terrain, const MaterialParams& material,
            const NumericsParams& numerics, double h_min);

    // Largest stable step for the current state: C * min(dx / max(|u| + a_x), dy / max(|v| + a_y))
    // over the wet cells; +infinity when nothing is wet.
    [[nodiscard]] double stable_dt(const State& s) const;

    // Advances the state by dt over the active box (recomputed from the state).
    void step(State& s, double dt);

    // stable_dt of the state the last step() left, computed by that step without a pass
    // of its own: the step's last operator takes the CFL rate of each row as it leaves
    // it, while the row is in the cache (docs/performance.md, "The CFL rate in the last
    // update"): an L S L step's second advection, an S L S step's closing friction
    // stage. Bit for bit stable_dt(s) of that state: the max is exact, and what an
    // advection does after its update (the thin-layer rule, the ghost cells) changes no
    // cell the rate counts. Empty where the step computed none (no cell to advect) and
    // for a state changed after the step: the caller knows that, the stepper does not.
    [[nodiscard]] std::optional<double> stable_dt_of_last_step() const { return dt_of_last_step_; }

    // Recomputes the active box from scratch (after the state was set from outside);
    // with `holding`, a box that holds every cell with material, searched in it only.
    void reset_active_box(const State& s);
    void reset_active_box(const State& s, const ActiveBox& holding);

    [[nodiscard]] const ActiveBox& active_box() const { return box_; }
    [[nodiscard]] double h_min() const { return h_min_; }
    // Volume that left the domain through open edges since construction (m^3).
    [[nodiscard]] double outflow_volume() const { return outflow_volume_; }
    void set_outflow_volume(double v) { outflow_volume_ = v; }
    // Energy budget per unit mass (m^2/s^2) behind the speed cap: fixed by the first
    // step() from the state it starts from, +infinity (no cap) until then. A restart
    // from a checkpoint must restore it to reproduce the uninterrupted run bitwise.
    [[nodiscard]] double energy_budget() const { return energy_budget_; }
    void set_energy_budget(double b) {
        energy_budget_ = b;
        budget_set_ = true;
    }
    // The Savage-Hutter regime of every cell (cell_rows.hpp, kRegimeXActive and
    // kRegimeYActive; the state's layout, ghost cells included): carried from advection
    // to advection, because a cell whose compression nothing confirms keeps its regime.
    // Empty until the first advection (every cell kRegimeAtStart). A restart from a
    // checkpoint must restore it to reproduce the uninterrupted run bitwise. A copy:
    // the stepper keeps the flags in another form (regime_).
    [[nodiscard]] CellVector<RegimeFlags> regime() const;
    void set_regime(const CellVector<RegimeFlags>& r);
    // With numerics.rest_faces: the cells the next advection counts as held at rest by
    // friction (rest_faces.hpp; the state's layout; empty before the first friction
    // stage). A restart from a checkpoint restores it, as the regimes.
    [[nodiscard]] CellVector<HeldFlag> held_at_rest() const;
    void set_held_at_rest(CellVector<HeldFlag> held);
    // The budget of a state: max over wet cells of
    //   |u|^2/2 + g (z_b + h_n g/g_n) + 2 k_max g_n h_n.
    [[nodiscard]] double energy_budget_of(const State& s) const;
    // Number of cell updates performed (active cells x steps).
    [[nodiscard]] std::uint64_t cell_updates() const { return cell_updates_; }
    // Of those, the cells the bands computed (make_bands): the rest, empty cells and
    // settled films, the step gives back unchanged without computing them.
    [[nodiscard]] std::uint64_t band_cell_updates() const { return band_cell_updates_; }

    // Small active areas (the cells of the bands, since settled films are left out of
    // them) run on one thread: a parallel region costs tens of microseconds to wake the
    // team, more than the work of a few thousand cells, and on a shared machine a
    // descheduled thread stalls every region (a 0.5 s test took 10 s on two threads).
    // Results do not depend on it. (Simulation's per-step passes use the same
    // threshold.) 4 000 since the strips (a step of 4 000 cells is about 0.5 ms of
    // work): against 20 000, two threads ran the demo in 8.6-11 s instead of 15-19 s,
    // the chute 18-20 % and the valley 45-55 % faster (docs/performance.md).
    static constexpr std::size_t kMinCellsPerThreadedStep = 4000;
    // The ghost columns of fewer rows are filled on one thread (fill_ghosts_near).
    static constexpr int kMinRowsPerThreadedGhostFill = 256;

    // The bands of the active box the advection works on this step (make_bands), and a
    // switch that makes it work on the whole box as one band: for the tests that
    // compare the two to the bit (test_active_bands.cpp).
    [[nodiscard]] const std::vector<ActiveBox>& bands() const { return bands_; }
    void set_whole_box_advection(bool whole) { whole_box_advection_ = whole; }
    // Shares of strips the advection's threads took from one another (StripClaims), over
    // every advection so far; and a switch that gives every strip to the first thread
    // at the start of each advection and has it wait until the others have claimed, so
    // that they begin by taking from it whatever the machine's load: for the tests that
    // compare those runs to one thread's, to the bit.
    [[nodiscard]] std::uint64_t strip_steals() const { return strip_steals_; }
    void set_all_strips_to_first_thread(bool all) { all_strips_to_first_thread_ = all; }
    // Rows per strip for a band whose per-cell stage spans `columns` (its width and the
    // ghost layers on both sides): kStripRows, halved while the strip's buffers would
    // exceed kStripBufferBytes, down to kFewestStripRows. Wide bands get short strips so
    // that a strip's buffers stay in the caches (docs/performance.md, "Strips as short
    // as wide bands need"); 4-row strips gained nothing measurable over 8 on bands 3000
    // to 6000 columns wide ("Strips of any height"). Results do not depend on it. The
    // switch fixes every band's strips at `rows` (1 to kStripRows; 0: by width) for the
    // tests that compare them to the bit.
    [[nodiscard]] static int strip_rows_for(int columns, bool waf);
    void set_strip_rows(int rows);
    static constexpr int kStripRows = 16, kFewestStripRows = 8;
    static constexpr std::size_t kStripBufferBytes = std::size_t{8} << 20;
    // The rows a segment's first and last strips hold back at their inner end until every
    // segment is done (advect()): updated state rows, which the neighbouring segment's
    // strips read; and new regimes of rows whose regimes that segment computes too, from
    // the previous ones (keep_regime_row: writing them while it reads would be a data
    // race, though the values would agree). Then the most rows beyond its own that a
    // strip has read of the state, and computed regimes of, in the advections so far
    // (advect_strip's row ranges): the counts held back must cover them, which
    // test_advection_strips.cpp checks.
    static constexpr int kStateRowsReadBeyond = 5;
    static constexpr int kRegimeHeldRows = 4;
    // How far ahead, in rows, a thread must know where its segment ends (advect()): the
    // strips reserved to it after each one it claims (StripClaims) span at least this
    // many rows. A strip then knows the end wherever its own rows are among the
    // segment's last kStateRowsReadBeyond, which wait, or a regime row it computes (two
    // past its end at most) is among the last kRegimeHeldRows: 5 and 2 + 4 + 1 = 7 rows,
    // fewer than these 9. So a strip of any height holds back what it must, the held
    // rows spanning several strips where strips are short. (Before, one strip was
    // reserved and had to hold them all: strips fixed at 3 rows changed
    // bench_equivalence's hashes.)
    static constexpr int kRowsKnownAhead = kStateRowsReadBeyond + kRegimeHeldRows;
    [[nodiscard]] int state_rows_read_beyond() const { return state_rows_read_beyond_; }
    [[nodiscard]] int regime_rows_beyond() const { return regime_rows_beyond_; }

    // The operators, public for tests of the splitting.
    void advect(State& s, double tau);
    void apply_sources(State& s, double dt);
    void fill_ghosts(State& s) const;  // every ghost cell

  private:
    // Scratch of one strip of rows of the advection (advection.cpp): every array has
    // the grid's row stride. The strip's rows [base, base + rows) are its positions 0 ..
    // rows - 1, and buffer index k(i, r) is one numbering of them for every array; each
    // array holds only the positions its stage computes and reads (StripRows).
    // Their pages are made where the stages write (PageVector): only the columns of the
    // box on a wide grid with a small flow.
    // A thread works through consecutive strips, and the rows a strip shares with the
    // next (one below its end, three above) are moved down and kept, so every stage
    // row is computed once per thread.
    struct StripBuffers {
        // One stage field: the positions [first_row, end_row) of the strip, at row_stride.
        // Element k(i, r) is at(k(i, r)); a row kernel gets at() of the row's column 0
        // and reads the rows next to it through the stride, so a row it reads must lie
        // within the array's positions too (advection.cpp derives each array's from the
        // row ranges of advect_strip).
        struct StripRows {
            PageVector<double> v;
            std::ptrdiff_t first = 0;  // k of v[0]
            void allocate(std::ptrdiff_t row_stride, int first_row, int end_row) {
                first = static_cast<std::ptrdiff_t>(first_row) * row_stride;
                v = PageVector<double>(static_cast<std::size_t>(row_stride) *
                                       static_cast<std::size_t>(end_row - first_row));
            }
            [[nodiscard]] double* at(std::ptrdiff_t k) { return v.data() + (k - first); }
            [[nodiscard]] const double* at(std::ptrdiff_t k) const { return v.data() + (k - first); }
            double& operator[](std::ptrdiff_t k) { return *at(k); }
            double operator[](std::ptrdiff_t k) const { return *at(k); }
        };
        std::ptrdiff_t stride = 0;
        int column0 = 0, base = 0, rows = 0;  // column0: column 0's position in a row
        StripRows su, sv;  // the state's velocity quotients hu / h, hv / h
        StripRows cx, cy;  // k_x p_x and k_y p_y per cell
        StripRows ax, ay;  // celerities sqrt(cx h), sqrt(cy h) (0 on thin cells)
        StripRows u_lo, u_hi, v_lo, v_hi, speed_hi;  // invariant bounds (u -/+ 2a_x, ...)
        StripRows yfo_h, yfo_qn, yfo_qt;     // first-order y-faces of the y-predictor
        StripRows pred_h, pred_hu, pred_hv;  // state advanced by the x-predictor
        StripRows pred_u, pred_v;            // and its velocity quotients
        StripRows pred_a;                    // and its celerity in y, sqrt(cy h)
        StripRows fx_h, fx_hu, fx_hv;        // x-face fluxes; face (i, r) left of cell i
        StripRows fy_h, fy_hu, fy_hv;        // y-face fluxes; face (i, r) below cell r
        StripRows factor;                    // donor factors
        StripRows out_h, out_hu, out_hv;     // the strip's updated rows that wait
        // Updated rows of a segment's first or last strip that a neighbouring segment's
        // strips read, and which must wait until every segment is done (advect()): rows
        // [j0, j1), columns [i0, i1), row j0 first.
        struct WaitingRows {
            int j0 = 0, j1 = 0, i0 = 0, i1 = 0;
            std::vector<double> h, hu, hv;
            // Index of cell (i, j), j0 <= j < j1, i0 <= i < i1, in h, hu, hv.
            [[nodiscard]] std::ptrdiff_t at(int i, int j) const {
                return static_cast<std::ptrdiff_t>(j - j0) * (i1 - i0) + (i - i0);
            }
        };
        // The thread's waiting rows of this advection: waiting[0 .. waiting_used).
        std::vector<WaitingRows> waiting;
        int waiting_used = 0;
        // The regime of the row the pressure stage computes next (column 0 at ng): its
        // previous regime, then the new one (regime_row_into).
        std::vector<RegimeFlags> regime_row;
        // The regime rule's terms (regime_rows.hpp: wet, still in x, still in y) of the rows
        // r - 2 .. r + 2 around the next regime row r, in rings of kRegimeRingRows rows
        // indexed by grid row (ring_row), so that each row's are computed once per block
        // of strips, not once for each of the five regime rows that read them. Rows
        // [.., terms_end) are computed (regime_row_into).
        PageVector<double> term_wet, term_still_x, term_still_y;  // (PageVector: rows aligned)
        int terms_end = 0;
        static constexpr int kRegimeRingRows = 8;
        // Column 0 of grid row r of a ring.
        [[nodiscard]] double* ring_row(PageVector<double>& a, int r) const {
            const int slot = ((r % kRegimeRingRows) + kRegimeRingRows) % kRegimeRingRows;
            return a.data() + static_cast<std::ptrdiff_t>(slot) * stride + column0;
        }
        // The update rows [block_j0, block_j1) of the segment the thread works on (its
        // strips of one band, advect()): which new regime rows are the segment's to
        // store, and which must wait (keep_regime_row).
        // block_j1 is a lower bound while the segment's end is not yet fixed (advect()).
        int block_j0 = 0, block_j1 = 0;
        // New regime rows that must wait until every segment is done: row held_rows[q],
        // columns [held_cols[q].first, held_cols[q].second), at held_regime[q * stride]
        // (column 0 at ng).
        std::vector<RegimeFlags> held_regime;
        std::vector<int> held_rows;
        std::vector<std::pair<int, int>> held_cols;
        PageVector<double> row_h, row_hu, row_hv, row_u, row_v,
            row_a;  // one row: the y-predictor's scratch (row_a: celerity in x)
        // Rows computed so far of each stage (end, exclusive), valid while the next
        // strip starts at carried_for.
        int carried_for = 0;
        int vel_end = 0, p_end = 0, yfo_end = 0, xf_end = 0, xp_end = 0, yf_end = 0, fac_end = 0;
        // The most rows beyond its own that a strip of this thread read of the state, and
        // computed regimes of (Stepper::state_rows_read_beyond, regime_rows_beyond).
        int rows_read_beyond = 0, regime_rows_beyond = 0;
        // The largest CFL rate of the rows this thread updated in this advection, when
        // the step asks for it (Stepper::take_cfl_rate_).
        double cfl_rate = 0.0;
        // Every array for its positions of a strip of strip_rows rows (at most kStripRows)
        // at row_stride, column 0 at column_zero (the state's layout, Field2D::column0); the
        // predictors' only with `predictors` (the WAF scheme).
        void allocate(std::ptrdiff_t row_stride, int column_zero, int strip_rows, bool predictors);
        // The invariant bounds hold "no bound" (kNoVelocityBound) until written, in the
        // columns [bounds_c0, bounds_c1) of every row (buffer positions, column -ng at 0),
        // which cover_columns widens to [c0, c1) before a stage reads them.
        int bounds_c0 = 0, bounds_c1 = 0;
        void cover_columns(int c0, int c1);
        // Moves the rows the next strip needs down by `by` rows (the strip height),
        // columns [i0, i1); the predictors' rows only for the WAF scheme.
        void carry_rows(int by, bool waf, int i0, int i1);
        [[nodiscard]] std::ptrdiff_t k(int i, int r) const {
            return static_cast<std::ptrdiff_t>(r - base) * stride + (column0 + i);
        }
    };

    void fill_ghosts_near(State& s, const ActiveBox& near) const;
    void pressure_row(const State& s, int r, int ia, int ib, StripBuffers& w) const;
    // The cells of the per-cell stage (regimes, velocity quotients, pressure) for the
    // active box b: b widened by the ghost layers, into the padding.
    [[nodiscard]] ActiveBox per_cell_box(const ActiveBox& b) const;
    // The new regime of row r, columns [ia, ib), into w.regime_row, from the state s
    // before the advection and the row's previous regime in regime_ (regime_row).
    // The velocity quotients of the rows whose terms it computes come too, while they
    // are the strip's next (w.vel_end) and below velocity_end (advect_strip, step 1).
    void regime_row_into(const State& s, double rest_speed, int r, int ia, int ib, int velocity_end,
                         StripBuffers& w) const;
    // The first row whose regime terms regime_row_into(r) computes: the terms of rows
    // r - 2 .. r + 2 (at the padding) that w's ring does not hold yet (w.terms_end).
    [[nodiscard]] int first_new_terms_row(const StripBuffers& w, int r) const;
    // Stores w.regime_row (row r, columns [ia, ib)) into regime_ if the row is the
    // thread's, at once or, where another thread still reads its previous regime, after
    // every block is done (advect()).
    void keep_regime_row(const State& s, int r, int ia, int ib, StripBuffers& w);
    // Advects rows [j_begin, j_end) of s over the columns [b.i0, b.i1) of their band;
    // b's rows are the box's, which bound every stage's rows. The updated rows go into
    // s itself, but for the first wait_first and the last wait_last, which another
    // segment's strips read: those go into w's waiting rows (advect()).
    void advect_strip(State& s, double tau, const ActiveBox& b, int j_begin, int j_end,
                      StripBuffers& w, int wait_first, int wait_last);
    void thin_layer_velocities(State& s) const;
    void shrink_box_to_wet(const State& s, const ActiveBox& search);
    // Cuts box_ into bands_ (from row_first_ and row_last_).
    void make_bands();
    [[nodiscard]] double energy_budget_in(const State& s, const ActiveBox& wet) const;
    // Square of the largest true speed the energy budget allows at bed elevation z
    // (negative: the cell lies above what the material can reach).
    [[nodiscard]] double speed_cap2(double z) const {
        return 2.0 * (energy_budget_ - numerics_.gravity * z);
    }

    Grid grid_;
    const TerrainFields& terrain_;
    MaterialParams material_;
    NumericsParams numerics_;
    EarthPressureCoefficients k_;
    double tan_delta_;
    double h_min_;

    ActiveBox box_;                     // cells updated this step
    ActiveBox wet_box_;                 // bounding box of cells with h > 0
    // box_ cut into bands of kBandStrips strips (rows), each only as wide as the cells
    // within the margin of the material of its rows and of the margin's rows beyond
    // (adjacent bands merged where cutting saves little): the advection works on
    // these (make_bands). A band without such cells has no columns.
    std::vector<ActiveBox> bands_;
    static constexpr int kBandStrips = 4;
    // Per row j of the box, the columns [first, second) of its band (at row j - box_.j0;
    // first == second: none). The sources, the time step's rate and the thin-layer rule
    // work on these too (stepper.cpp).
    std::vector<std::pair<int, int>> band_columns_;
    bool whole_box_advection_ = false;
    bool all_strips_to_first_thread_ = false;
    std::uint64_t strip_steals_ = 0;
    // Per grid row, the first and last column of the cells the bands work on (last <
    // first: none), set by shrink_box_to_wet for the rows it searched: those with h > 0,
    // or, while films_settled_, those at least h_min thick.
    std::vector<int> row_first_, row_last_;
    // Whether every film (0 < h < h_min) without a cell at least h_min thick within the
    // margin is at rest with hu = hv = +0, so that a step of the bands of the thick cells
    // alone gives the state of the whole box to the bit: an advection's thin-layer rule
    // last wrote every film of its bands (and the films beyond them were at rest
    // already). A friction stage (which accelerates films down a slope) or a state set
    // from outside clears it: an S L S step, which ends with one, and a run's first
    // step keep the bands of the material (docs/numerics.md, "Active region").
    bool films_settled_ = false;
    std::vector<StripBuffers> strips_;  // one per thread
    int fixed_strip_rows_ = 0;          // set_strip_rows
    // state_rows_read_beyond(), regime_rows_beyond().
    int state_rows_read_beyond_ = 0, regime_rows_beyond_ = 0;
    double k_max_;          // largest earth-pressure coefficient
    double energy_budget_;  // see energy_budget(); +infinity = not set
    bool budget_set_ = false;
    bool threaded_ = false;
    // The operator takes the CFL rate of the rows it leaves (the step's last: the second
    // advection of L S L, the closing friction stage of S L S), and what that gave:
    // stable_dt_of_last_step().
    bool take_cfl_rate_ = false;
    std::optional<double> dt_of_last_step_;
    [[nodiscard]] double dt_of_rate(double rate) const;  // C / rate, +infinity for 0
    // The conservative celerity coefficients of the CFL rate (stable_dt) and the rate of
    // row j over its band's columns.
    [[nodiscard]] std::pair<double, double> cfl_k() const;
    [[nodiscard]] double cfl_rate_of_row(const State& s, int j, int i0, int i1) const;
    double outflow_volume_ = 0.0;
    std::array<std::vector<double>, 4>
        edge_outflow_;  // per face of the west, east, south, north edges
    std::uint64_t cell_updates_ = 0, band_cell_updates_ = 0;
    // The regimes of regime(), each XOR kRegimeAtStart (stored_regime): a cell at start
    // holds 0, so the grid's flags are made without writing them and only the rows the
    // flow reaches are ever touched (field_storage.hpp). Assigning kRegimeAtStart to
    // every cell at the first advection took 7 ms of benchmark (d)'s 79 ms run.
    CellVector<StoredRegime> regime_;
    // numerics.rest_faces (rest_faces.hpp): held_ marks the cells the last friction stage
    // stopped; held_quiet_ those of them no mass entered or left in the advection after
    // it, for the next step's first advection under L S L (the one after S reads held_).
    // after_sources_: the last operator was the friction stage.
    CellVector<HeldFlag> held_, held_quiet_;
    bool after_sources_ = false;
    // This advection's flags: those it reads (null: rest_faces off, or no friction stage
    // yet) and those it writes (null: none).
    const HeldFlag* rest_in_ = nullptr;
    HeldFlag* rest_out_ = nullptr;
    void hold_rest_faces(const State& s, const StripBuffers& w, const HeldFlag* held, bool x_faces,
                         int r, int i0, int i1, double* fh, double* fn, double* ft) const;
};

}  // namespace avalanche
