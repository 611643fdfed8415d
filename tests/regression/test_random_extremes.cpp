// The extreme-case matrix's random sweep (issue "Speed against accuracy", item 5): scenes
// that draw every parameter at once (random_scenes.hpp), each run three ways:
//   - FiniteNonNegativeConservativeAndBelowFreeFall: the matrix's checks (no NaN/Inf,
//     no negative depth, mass conserved to round-off with the outflow counted, every
//     speed below the scene's free-fall bound), through Simulation::run;
//   - BandsGiveTheWholeBoxsRunToTheBit: the advection's bands against the whole box;
//   - MirroredSceneGivesTheMirroredRun: the scene mirrored in x and in y.
//
// CI runs seeds 1 to 200 (about 20 s of the three on one thread). A longer sweep,
// `cmake --build build --target random-extremes-study` (5000 seeds), or
//   AVALANCHE_RANDOM_EXTREMES=5000 build/tests/regression/test_regression
//       --gtest_filter='Seeds/RandomSweep*'
// A failing seed prints every parameter of its scene.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <iostream>
#include <string>
#include <vector>

#include "avalanche/core/simulation.hpp"
#include "avalanche/numerics/stepper.hpp"
#include "extreme_checks.hpp"
#include "random_scenes.hpp"
#include "support/same_bits.hpp"

using namespace avalanche;
using namespace avalanche::extremes;
using avalanche::test::same_bits;

namespace {

constexpr std::uint64_t kCiSeeds = 200;
// Steps of each band comparison: enough for fronts to cross small grids and for films
// to settle behind them.
constexpr int kBandSteps = 400;
// Steps of each mirror comparison (a first difference shows within a few steps).
constexpr int kMirrorSteps = 200;

std::vector<std::uint64_t> seeds() {
    std::uint64_t count = kCiSeeds;
    if (const char* env = std::getenv("AVALANCHE_RANDOM_EXTREMES"))
        count = std::strtoull(env, nullptr, 10);
    std::vector<std::uint64_t> out;
    for (std::uint64_t s = 1; s <= count; ++s) out.push_back(s);
    return out;
}

class RandomSweep : public ::testing::TestWithParam<std::uint64_t> {};

TEST_P(RandomSweep, FiniteNonNegativeConservativeAndBelowFreeFall) {
    const RandomScene r = random_scene(GetParam());
    SCOPED_TRACE(r.description);
    EXPECT_TRUE(run_and_check(r.scene, "[random extremes] seed " + std::to_string(GetParam())));
    if (::testing::Test::HasFailure())
        std::cout << "[random extremes] failed: " << r.description << "\n";
}

// The advection's bands (Stepper::make_bands: each only as wide as its rows' material
// needs, cut around the thick cells once the films are settled) must give the run over
// the whole box to the bit: the state, the outflow, the Savage-Hutter regimes and the
// faces held at rest, step after step. The random scenes put films, towers, pits, walls
// and several releases where test_active_bands.cpp has one valley.
TEST_P(RandomSweep, BandsGiveTheWholeBoxsRunToTheBit) {
    const RandomScene r = random_scene(GetParam());
    const Scene& scene = r.scene;
    SCOPED_TRACE(r.description);
    const double h_min = effective_h_min(scene.numerics, scene.initial, scene.terrain);
    struct Run {
        State state;
        double outflow = 0.0;
        CellVector<RegimeFlags> regime;
        CellVector<HeldFlag> held;
        int steps = 0;
        long band_cells = 0, box_cells = 0;
    };
    const auto run = [&](bool whole_box) {
        Run out;
        out.state = scene.initial;
        Stepper stepper(scene.grid, scene.terrain, scene.material, scene.numerics, h_min);
        stepper.set_whole_box_advection(whole_box);
        stepper.reset_active_box(out.state);
        double t = 0.0;
        for (; out.steps < kBandSteps && t < scene.numerics.t_end; ++out.steps) {
            // No finite step: the material is at rest (Simulation::run ends there).
            const double dt = stepper.stable_dt(out.state);
            if (!std::isfinite(dt)) break;
            stepper.step(out.state, dt);
            t += dt;
            for (const ActiveBox& b : stepper.bands()) out.band_cells += b.cells();
            out.box_cells += stepper.active_box().cells();
        }
        out.outflow = stepper.outflow_volume();
        out.regime = stepper.regime();
        out.held = stepper.held_at_rest();
        return out;
    };
    const Run whole = run(true), bands = run(false);
    ASSERT_EQ(whole.steps, bands.steps);
    EXPECT_TRUE(same_bits(whole.state.h, bands.state.h));
    EXPECT_TRUE(same_bits(whole.state.hu, bands.state.hu));
    EXPECT_TRUE(same_bits(whole.state.hv, bands.state.hv));
    EXPECT_TRUE(same_bits(whole.outflow, bands.outflow));
    EXPECT_TRUE(std::equal(whole.regime.begin(), whole.regime.end(), bands.regime.begin(),
                           bands.regime.end(), [](const RegimeFlags& a, const RegimeFlags& b) {
                               return std::memcmp(&a, &b, sizeof a) == 0;
                           }));
    EXPECT_TRUE(
        std::equal(whole.held.begin(), whole.held.end(), bands.held.begin(), bands.held.end()));
    std::cout << "[random bands] seed " << GetParam() << ": " << bands.steps
              << " steps, bands over box "
              << static_cast<double>(bands.band_cells) / bands.box_cells << "\n";
}

// A scene mirrored across either centre line must give the mirrored run, every value of
// the state equal after every step: the kernels pair their sums so that a mirrored
// problem adds the same numbers (docs/numerics.md, "Symmetry and determinism"), and so
// must the terrain's derivatives (dem_frame.cpp), the bands, the thin-layer rule's
// search, the regimes and the faces held at rest, which the random scenes all reach.
TEST_P(RandomSweep, MirroredSceneGivesTheMirroredRun) {
    const RandomScene r = random_scene(GetParam());
    const Scene& scene = r.scene;
    SCOPED_TRACE(r.description);
    for (Axis axis : {Axis::x, Axis::y}) {
        const Scene mirror = mirrored(scene, axis);
        const double h_min = effective_h_min(scene.numerics, scene.initial, scene.terrain);
        ASSERT_EQ(h_min, effective_h_min(mirror.numerics, mirror.initial, mirror.terrain));
        State a = scene.initial, b = mirror.initial;
        Stepper sa(scene.grid, scene.terrain, scene.material, scene.numerics, h_min);
        Stepper sb(mirror.grid, mirror.terrain, mirror.material, mirror.numerics, h_min);
        sa.reset_active_box(a);
        sb.reset_active_box(b);
        for (int k = 0; k < kMirrorSteps; ++k) {
            const double dt = sa.stable_dt(a);
            ASSERT_EQ(dt, sb.stable_dt(b)) << "step " << k;
            if (!std::isfinite(dt)) break;
            sa.step(a, dt);
            sb.step(b, dt);
            ASSERT_TRUE(mirror_images(a, b, axis))
                << "mirrored in " << (axis == Axis::x ? "x" : "y") << ", step " << k;
        }
    }
}

INSTANTIATE_TEST_SUITE_P(Seeds, RandomSweep, ::testing::ValuesIn(seeds()),
                         [](const ::testing::TestParamInfo<std::uint64_t>& info) {
                             return "seed" + std::to_string(info.param);
                         });

}  // namespace
