// Google Benchmark of the solver's inner kernels (docs/performance.md):
//   - the HLLC fan (wave speeds and the four fluxes) and the Godunov flux from it,
//   - the WAF flux from a fan,
//   - one full Stepper::step (L S L) on a small wet grid, 1 and 2 OpenMP threads,
//   - the source step Stepper::apply_sources alone (chute frame, and DEM frame with
//     the metric and curvature terms).
// Face kernels run over a batch of 4096 varied face states, so that the branches
// and the loads look like a sweep, not like one state in registers.
#include <benchmark/benchmark.h>

#include <cmath>
#include <numbers>
#include <random>
#include <vector>

#ifdef _OPENMP
#include <omp.h>
#endif

#include "avalanche/core/simulation.hpp"
#include "avalanche/numerics/riemann_hllc.hpp"
#include "avalanche/numerics/stepper.hpp"
#include "avalanche/physics/chute.hpp"
#include "avalanche/physics/dem_frame.hpp"
#include "avalanche/physics/release.hpp"

using namespace avalanche;

namespace {

constexpr int kFaces = 4096;
constexpr double kGravity = 9.81;

struct Face {
    Conserved l, r;
    double c_l, c_r;
};

// Wet face states of a flowing avalanche: depths 0.1-3 m, speeds -5..15 m/s.
std::vector<Face> make_faces() {
    std::mt19937_64 rng(42);
    std::uniform_real_distribution<double> depth(0.1, 3.0), speed(-5.0, 15.0), c(5.0, 15.0);
    std::vector<Face> f(kFaces);
    for (Face& x : f) {
        const double hl = depth(rng), hr = depth(rng);
        x.l = {hl, hl * speed(rng), hl * speed(rng)};
        x.r = {hr, hr * speed(rng), hr * speed(rng)};
        x.c_l = c(rng);
        x.c_r = c(rng);
    }
    return f;
}

void bm_hllc_fan(benchmark::State& state) {
    const std::vector<Face> faces = make_faces();
    for (auto _ : state) {
        for (const Face& x : faces) {
            HllcFan fan = hllc_fan(x.l, x.r, x.c_l, x.c_r, 1e-6);
            benchmark::DoNotOptimize(fan);
        }
    }
    state.SetItemsProcessed(state.iterations() * kFaces);
}
BENCHMARK(bm_hllc_fan);

void bm_hllc_flux(benchmark::State& state) {
    const std::vector<Face> faces = make_faces();
    for (auto _ : state) {
        for (const Face& x : faces) {
            Conserved g = hllc_flux(x.l, x.r, x.c_l, x.c_r, 1e-6);
            benchmark::DoNotOptimize(g);
        }
    }
    state.SetItemsProcessed(state.iterations() * kFaces);
}
BENCHMARK(bm_hllc_flux);

// The fan plus the WAF weights and sum; the limiter values are given (the stepper
// computes them from the neighbours), so this is the cost of eq. 9 itself.
void bm_waf_flux(benchmark::State& state) {
    const std::vector<Face> faces = make_faces();
    const double psi[3] = {0.8, 1.0, 0.6};
    for (auto _ : state) {
        for (const Face& x : faces) {
            const HllcFan fan = hllc_fan(x.l, x.r, x.c_l, x.c_r, 1e-6);
            Conserved g = waf_flux(fan, 0.01, psi);
            benchmark::DoNotOptimize(g);
        }
    }
    state.SetItemsProcessed(state.iterations() * kFaces);
}
BENCHMARK(bm_waf_flux);

// A small wet grid: n x n cells of 0.5 m on a 35 deg chute plane, a 0.5 m layer
// everywhere plus a 2 m paraboloid, so the limiters and active/passive switch work.
struct WetGrid {
    ChuteGeometry chute;
    Grid grid;
    TerrainFields terrain;
    State initial;

    explicit WetGrid(int n) {
        chute.slope_deg = 35.0;
        chute.length = chute.width = 0.5 * n;
        grid = chute_grid(chute, 0.5);
        terrain = chute_terrain(chute, grid, kGravity);
        Field2D h =
            rasterize_release(ParaboloidRelease{{0.25 * n, 0.25 * n}, 0.1 * n, 2.0}, grid, 2);
        for (double& v : h.raw()) v += 0.5;
        initial = state_at_rest(grid, h, terrain);
    }
};

void set_threads(int n) {
#ifdef _OPENMP
    omp_set_num_threads(n);
#else
    (void)n;
#endif
}

// One Stepper::step: L(dt/2) S(dt) L(dt/2) on the whole wet grid. The state is reset
// before each step (outside the timing), so every iteration does the same work.
void bm_stepper_step(benchmark::State& state) {
    const int n = static_cast<int>(state.range(0));
    const auto scheme = state.range(1) == 0 ? Scheme::waf : Scheme::godunov;
    set_threads(static_cast<int>(state.range(2)));
    const WetGrid w(n);
    NumericsParams num;
    num.scheme = scheme;
    Stepper stepper(w.grid, w.terrain, MaterialParams{}, num,
                    effective_h_min(num, w.initial, w.terrain));
    State s = w.initial;
    stepper.reset_active_box(s);
    const double dt = stepper.stable_dt(s);
    for (auto _ : state) {
        state.PauseTiming();
        s = w.initial;
        state.ResumeTiming();
        stepper.step(s, dt);
        benchmark::ClobberMemory();
    }
    state.SetItemsProcessed(state.iterations() * static_cast<std::int64_t>(n) * n);
    state.SetLabel(scheme == Scheme::waf ? "waf" : "godunov");
    set_threads(1);
}
BENCHMARK(bm_stepper_step)
    ->ArgNames({"n", "godunov", "threads"})
    ->ArgsProduct({{128, 512}, {0, 1}, {1, 2}})
    ->Unit(benchmark::kMicrosecond)
    ->UseRealTime();

// The source step alone. Chute frame: gravity and friction. DEM frame (a curved
// bowl): the true-speed metric and the centripetal load are added.
void bm_apply_sources(benchmark::State& state) {
    const int n = static_cast<int>(state.range(0));
    const bool dem = state.range(1) != 0;
    set_threads(1);
    const WetGrid w(n);
    TerrainFields bowl;
    if (dem) {
        std::vector<double> z(w.grid.cells());
        for (int j = 0; j < n; ++j)
            for (int i = 0; i < n; ++i)
                z[static_cast<std::size_t>(j) * n + i] =
                    0.02 * (std::pow(w.grid.x_center(i) - 0.25 * n, 2) +
                            std::pow(w.grid.y_center(j), 2)) -
                    0.7 * w.grid.x_center(i);
        bowl = dem_terrain(w.grid, z, kGravity);
    }
    const TerrainFields& terrain = dem ? bowl : w.terrain;
    NumericsParams num;
    Stepper stepper(w.grid, terrain, MaterialParams{}, num, 1e-5);
    State s = state_at_rest(
        w.grid, rasterize_release(BoxRelease{{0.0, 0.5 * n}, {0.0, 0.5 * n}, 1.0}, w.grid, 2),
        terrain);
    for (int j = 0; j < n; ++j)
        for (int i = 0; i < n; ++i)
            s.hu(i, j) = s.hv(i, j) = 3.0 * s.h(i, j);  // moving: friction acts
    stepper.reset_active_box(s);
    const State moving = s;
    for (auto _ : state) {
        state.PauseTiming();
        s = moving;
        state.ResumeTiming();
        stepper.apply_sources(s, 1e-3);
        benchmark::ClobberMemory();
    }
    state.SetItemsProcessed(state.iterations() * static_cast<std::int64_t>(n) * n);
    state.SetLabel(dem ? "dem (metric, curvature)" : "chute");
}
BENCHMARK(bm_apply_sources)
    ->ArgNames({"n", "dem"})
    ->ArgsProduct({{512}, {0, 1}})
    ->Unit(benchmark::kMicrosecond);

}  // namespace

BENCHMARK_MAIN();
