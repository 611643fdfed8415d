// The advection works on bands of the active box, each as wide as the material of its
// rows needs (Stepper::make_bands): it must give the state, the outflow and the
// Savage-Hutter regimes of the advection over the whole box, to the bit, on one thread
// and on two. Two flows on a rough valley, one high on the west side and one low on the
// east side that leaves through the open north edge, so that the box is much wider
// than either flow and the bands between them have no columns at all. The flows leave
// films (0 < h < h_min) behind them, which the bands of an L S L step leave out once
// they are settled (Stepper::films_settled_): with the faces friction holds and without,
// and under S L S, whose films keep the friction stage's momentum and stay in the bands.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstring>
#include <vector>

#include "avalanche/numerics/stepper.hpp"
#include "avalanche/output/hazard_maps.hpp"
#include "avalanche/physics/dem_frame.hpp"
#include "avalanche/physics/release.hpp"
#include "rough_valley.hpp"
#include "support/analytic_harness.hpp"
#include "support/same_bits.hpp"

using namespace avalanche;

namespace {

constexpr double kG = 9.81;

using avalanche::test::same_bits;

constexpr double kHMin = 1e-4;

// The scene of every test: a valley falling to the north (+y) at 45 degrees, with a
// rough surface.
const Grid kValley{200, 330, 5.0, 5.0, 0.0, 0.0};

TerrainFields valley_terrain() {
    return dem_terrain(kValley, avalanche::testing::rough_valley(kValley, 1.0, 0.001), kG);
}

// The two flows at rest; with one_flow, only the high one.
State release(const TerrainFields& t, bool one_flow) {
    const Grid& g = kValley;
    Field2D h0 =
        rasterize_release(ParaboloidRelease{{0.25 * g.x_max(), 0.2 * g.y_max()}, 30.0, 3.0}, g);
    const Field2D low =
        rasterize_release(ParaboloidRelease{{0.75 * g.x_max(), 0.94 * g.y_max()}, 30.0, 3.0}, g);
    for (int j = 0; j < g.ny && !one_flow; ++j)
        for (int i = 0; i < g.nx; ++i) h0(i, j) += low(i, j);
    return state_at_rest(g, h0, t);
}

struct BandedRun {
    State state;
    double outflow = 0.0;
    CellVector<RegimeFlags> regime;
    CellVector<HeldFlag> held;
    std::size_t most_bands = 0;   // the most bands with columns in one step
    double band_fraction = 1.0;   // cells of the bands over cells of the box, summed over the steps
    double films = 0.0;           // films of the box at the steps' starts, summed over the steps
    double films_left_out = 0.0;  // those of them outside every band
    int one_narrow_band = 0;      // steps with one band, narrower than the box
};

// Whether cell (i, j) lies in one of the bands.
bool in_a_band(const std::vector<ActiveBox>& bands, int i, int j) {
    for (const ActiveBox& b : bands)
        if (i >= b.i0 && i < b.i1 && j >= b.j0 && j < b.j1) return true;
    return false;
}

// With one_flow, only the high one: then the bands are often one, narrower than the box.
BandedRun run(const TerrainFields& t, bool whole_box, int steps,
              const NumericsParams& n = {},  // the defaults: open edges, L S L
              bool one_flow = false) {
    BandedRun r;
    r.state = release(t, one_flow);
    const MaterialParams m;  // Savage-Hutter earth pressure: regimes carried
    Stepper stepper(kValley, t, m, n, kHMin);
    stepper.set_whole_box_advection(whole_box);
    // Every cell starts passive in both directions, as the cells a flow has left keep
    // the regimes it gave them: the whole box gives its empty cells the regime at
    // start, and so must the bands to the cells of the box they leave out.
    stepper.set_regime(CellVector<RegimeFlags>(r.state.h.raw().size()));
    stepper.reset_active_box(r.state);
    double band_cells = 0.0, box_cells = 0.0;
    for (int k = 0; k < steps; ++k) {
        const State before = r.state;
        stepper.step(r.state, stepper.stable_dt(r.state));
        // The films at the step's start, and those the step's bands left out.
        const ActiveBox box = stepper.active_box();
        for (int j = box.j0; j < box.j1; ++j)
            for (int i = box.i0; i < box.i1; ++i) {
                const double h = before.h(i, j);
                if (!(h > 0.0 && h < kHMin)) continue;
                r.films += 1.0;
                r.films_left_out += in_a_band(stepper.bands(), i, j) ? 0.0 : 1.0;
            }
        std::size_t with_columns = 0;
        for (const ActiveBox& b : stepper.bands()) {
            band_cells += static_cast<double>(b.cells());
            with_columns += b.empty() ? 0 : 1;
        }
        box_cells += static_cast<double>(stepper.active_box().cells());
        r.most_bands = std::max(r.most_bands, with_columns);
        const std::vector<ActiveBox>& bands = stepper.bands();
        if (bands.size() == 1 && bands.front().i1 - bands.front().i0 < box.i1 - box.i0)
            ++r.one_narrow_band;
    }
    r.outflow = stepper.outflow_volume();
    r.regime = stepper.regime();
    r.held = stepper.held_at_rest();
    r.band_fraction = band_cells / box_cells;
    return r;
}

void expect_same_run(const BandedRun& a, const BandedRun& b) {
    EXPECT_TRUE(same_bits(a.state.h, b.state.h));
    EXPECT_TRUE(same_bits(a.state.hu, b.state.hu));
    EXPECT_TRUE(same_bits(a.state.hv, b.state.hv));
    EXPECT_EQ(a.outflow, b.outflow);
    ASSERT_EQ(a.regime.size(), b.regime.size());
    EXPECT_EQ(std::memcmp(a.regime.data(), b.regime.data(), a.regime.size() * sizeof(RegimeFlags)), 0);
    ASSERT_EQ(a.held.size(), b.held.size());
    // Empty without the faces held at rest (no data to hand memcmp): compared element-wise.
    EXPECT_TRUE(std::equal(a.held.begin(), a.held.end(), b.held.begin()));
}

TEST(ActiveBands, GiveTheWholeBoxsStateOutflowAndRegimesToTheBit) {
    const TerrainFields t = valley_terrain();
    for (int n : {1, 2}) {
        const analytic::ScopedThreads threads(n);
        const BandedRun whole = run(t, true, 260);
        const BandedRun bands = run(t, false, 260);
        SCOPED_TRACE(n);
        expect_same_run(whole, bands);
        // The comparison says something: a flow left through the north edge, the
        // bands were several and covered well under the box.
        EXPECT_GT(whole.outflow, 0.0);
        EXPECT_EQ(whole.most_bands, 1u);
        EXPECT_GE(bands.most_bands, 3u);
        EXPECT_LT(bands.band_fraction, 0.7);
        // Films were left out of the bands, a good part of those the flows left.
        EXPECT_EQ(whole.films_left_out, 0.0);
        EXPECT_GT(bands.films_left_out, 0.1 * bands.films);
    }
}

// The same with the faces friction holds at rest, whose flags (held_at_rest) the steps
// carry too, and under S L S: its steps end with a friction stage, which moves the
// films on the steep valley, so its bands keep every film (and give the same bits).
TEST(ActiveBands, LeaveOutOnlySettledFilmsToTheBit) {
    const TerrainFields t = valley_terrain();
    const analytic::ScopedThreads threads(2);
    NumericsParams held;
    held.rest_faces = true;
    NumericsParams sls;
    sls.splitting = Splitting::sls;
    const NumericsParams lsl;
    for (const NumericsParams& n : {held, sls, lsl}) {
        const bool one_flow = !n.rest_faces && n.splitting == Splitting::lsl;
        SCOPED_TRACE(n.rest_faces ? "rest faces" : (one_flow ? "one flow" : "S L S"));
        const BandedRun whole = run(t, true, 260, n, one_flow);
        const BandedRun bands = run(t, false, 260, n, one_flow);
        expect_same_run(whole, bands);
        ASSERT_GT(bands.films, 0.0);
        if (n.splitting == Splitting::sls)
            EXPECT_EQ(bands.films_left_out, 0.0);
        else if (one_flow)  // the cells of the box beside the one band get the regime at start
            EXPECT_GT(bands.one_narrow_band, 10);
        else
            EXPECT_GT(bands.films_left_out, 0.1 * bands.films);
    }
}

// The hazard maps take in, after each step, only the cells of the step's bands
// (HazardMaps::on_step with SimulationView::changed): the cells of the box beside them,
// empty or settled films, kept the state the maps took in before. Two maps of one run,
// one fed the bands and one the whole box, must agree to the bit.
TEST(ActiveBands, HazardMapsOfTheBandsAreThoseOfTheWholeBox) {
    const Grid& g = kValley;
    const TerrainFields t = valley_terrain();
    State s = release(t, false);
    Stepper stepper(g, t, MaterialParams{}, NumericsParams{}, kHMin);
    stepper.reset_active_box(s);
    OutputParams out;
    out.h_threshold = 0.5 * kHMin;  // the films' depths are taken in as maxima too
    HazardMaps by_bands(g, out, 2000.0), by_box(g, out, 2000.0);
    by_bands.on_start(SimulationView{g, t, s, 0.0, 0, stepper.active_box()});
    by_box.on_start(SimulationView{g, t, s, 0.0, 0, stepper.active_box()});
    double time = 0.0, left_out = 0.0;  // box cells with material outside the bands
    for (int k = 1; k <= 260; ++k) {
        const double dt = stepper.stable_dt(s);
        stepper.step(s, dt);
        time += dt;
        const ActiveBox& box = stepper.active_box();
        by_bands.on_step(
            SimulationView{g, t, s, time, static_cast<std::uint64_t>(k), box, stepper.bands()});
        by_box.on_step(SimulationView{g, t, s, time, static_cast<std::uint64_t>(k), box});
        for (int j = box.j0; j < box.j1; ++j)
            for (int i = box.i0; i < box.i1; ++i)
                left_out += s.h(i, j) > 0.0 && !in_a_band(stepper.bands(), i, j) ? 1.0 : 0.0;
    }
    EXPECT_GT(left_out, 0.0);
    EXPECT_TRUE(same_bits(by_bands.max_depth(), by_box.max_depth()));
    EXPECT_TRUE(same_bits(by_bands.max_speed(), by_box.max_speed()));
    EXPECT_TRUE(same_bits(by_bands.arrival_time(), by_box.arrival_time()));
    EXPECT_EQ(by_bands.reach_box(), by_box.reach_box());
}

}  // namespace
