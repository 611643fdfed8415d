// The advection works on bands of the active box, each as wide as the material of its
// rows needs (Stepper::make_bands): it must give the state, the outflow and the
// Savage-Hutter regimes of the advection over the whole box, to the bit, on one thread
// and on two. Two flows on a rough valley, one high on the west side and one low on the
// east side that leaves through the open north edge, so that the box is much wider
// than either flow and the bands between them have no columns at all.
#include <gtest/gtest.h>
#include <omp.h>

#include <cstring>
#include <vector>

#include "avalanche/numerics/stepper.hpp"
#include "avalanche/physics/dem_frame.hpp"
#include "avalanche/physics/release.hpp"
#include "rough_valley.hpp"
#include "support/same_bits.hpp"

using namespace avalanche;

namespace {

constexpr double kG = 9.81;

using avalanche::test::same_bits;

// A valley falling to the north (+y) at 45 degrees, with a rough surface.
std::vector<double> rough_valley(const Grid& g) { return avalanche::testing::rough_valley(g, 1.0, 0.001); }

struct BandedRun {
    State state;
    double outflow = 0.0;
    CellVector<RegimeFlags> regime;
    std::size_t most_bands = 0;    // the most bands with columns in one step
    double band_fraction = 1.0;    // cells of the bands over cells of the box, summed over the steps
};

BandedRun run(const Grid& g, const TerrainFields& t, bool whole_box, int steps) {
    Field2D h0 = rasterize_release(ParaboloidRelease{{0.25 * g.x_max(), 0.2 * g.y_max()}, 30.0, 3.0}, g);
    const Field2D low = rasterize_release(ParaboloidRelease{{0.75 * g.x_max(), 0.94 * g.y_max()}, 30.0, 3.0}, g);
    for (int j = 0; j < g.ny; ++j)
        for (int i = 0; i < g.nx; ++i) h0(i, j) += low(i, j);
    BandedRun r{state_at_rest(g, h0, t), 0.0, {}, 0, 1.0};
    const MaterialParams m;  // Savage-Hutter earth pressure: regimes carried
    const NumericsParams n;  // open edges
    Stepper stepper(g, t, m, n, 1e-4);
    stepper.set_whole_box_advection(whole_box);
    // Every cell starts passive in both directions, as the cells a flow has left keep
    // the regimes it gave them: the whole box gives its empty cells the regime at
    // start, and so must the bands to the cells of the box they leave out.
    stepper.set_regime(CellVector<RegimeFlags>(r.state.h.raw().size()));
    stepper.reset_active_box(r.state);
    double band_cells = 0.0, box_cells = 0.0;
    for (int k = 0; k < steps; ++k) {
        stepper.step(r.state, stepper.stable_dt(r.state));
        std::size_t with_columns = 0;
        for (const ActiveBox& b : stepper.bands()) {
            band_cells += static_cast<double>(b.cells());
            with_columns += b.empty() ? 0 : 1;
        }
        box_cells += static_cast<double>(stepper.active_box().cells());
        r.most_bands = std::max(r.most_bands, with_columns);
    }
    r.outflow = stepper.outflow_volume();
    r.regime = stepper.regime();
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
}

TEST(ActiveBands, GiveTheWholeBoxsStateOutflowAndRegimesToTheBit) {
    const Grid g{200, 330, 5.0, 5.0, 0.0, 0.0};
    const std::vector<double> z = rough_valley(g);
    const TerrainFields t = dem_terrain(g, z, kG);
    const int threads = omp_get_max_threads();
    for (int n : {1, 2}) {
        omp_set_num_threads(n);
        const BandedRun whole = run(g, t, true, 260);
        const BandedRun bands = run(g, t, false, 260);
        SCOPED_TRACE(n);
        expect_same_run(whole, bands);
        // The comparison says something: a flow left through the north edge, the
        // bands were several and covered well under the box.
        EXPECT_GT(whole.outflow, 0.0);
        EXPECT_EQ(whole.most_bands, 1u);
        EXPECT_GE(bands.most_bands, 3u);
        EXPECT_LT(bands.band_fraction, 0.7);
    }
    omp_set_num_threads(threads);
}

}  // namespace
