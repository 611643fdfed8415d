// Google Benchmark of the solver's row kernels on rows that stay in the cache: the
// cost of each kernel's arithmetic per face or cell, without the memory traffic of a
// whole grid (docs/performance.md, "The cost floor of a cell update").
//
// Each benchmark runs its kernel over one row of kRow cells (three rows where the
// kernel reads the rows above and below), all inputs of a wet flowing layer: depths
// 0.5-2 m, speeds -5..15 m/s, no thin cell, no front. That is the interior of a flow,
// the case the throughput targets are about; the rare paths (fronts, clamps, caps)
// are not timed. The counter per_item is the kernel's cost in seconds per face or cell.
//
// The machine is shared and noisy: run with --benchmark_repetitions=N and read the
// "min" aggregate (the least disturbed repetition), e.g.
//   bench_row_kernels --benchmark_repetitions=10 --benchmark_report_aggregates_only=true
#include <benchmark/benchmark.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <random>
#include <string>
#include <vector>

#include "avalanche/core/field_storage.hpp"
#include "avalanche/numerics/cell_rows.hpp"
#include "avalanche/numerics/face_flux_rows.hpp"
#include "avalanche/numerics/update_rows.hpp"
#include "avalanche/physics/earth_pressure.hpp"
#include "avalanche/physics/material.hpp"
#include "min_statistic.hpp"

using namespace avalanche;
using avalanche::bench::min_of;

namespace {

constexpr int kRow = 512;  // cells per row: 9 arrays of 4 KB fit the 48 KB L1 data cache
// Columns beyond each end: the face stencils reach two cells; eight, so that column 0
// starts a cache line, as in the grid's fields and the strips' buffers (Field2D::column0).
constexpr int kPad = 8;
constexpr int kStride = kRow + 2 * kPad;

// Three rows (below, this, above) of one per-cell quantity; at(0) addresses column 0
// of the middle row, as the kernels expect.
struct Rows {
    PageVector<double> v = PageVector<double>(3 * kStride);  // page-aligned
    double* at(int row) { return v.data() + (row + 1) * kStride + kPad; }
    double* mid() { return at(0); }
};

// A wet flowing layer: per cell depth, velocities, momenta, pressure coefficients and
// celerities, and terrain rows of a DEM (metric) frame.
struct Layer {
    Rows h, hu, hv, u, v, c, a, px, py, gn, nt, sx, sy, ax, ay, elevation;
    Layer() {
        std::mt19937_64 rng(2026);
        std::uniform_real_distribution<double> depth(0.5, 2.0), speed(-5.0, 15.0), cross(-5.0, 5.0),
            coef(5.0, 15.0), slope(-0.5, 0.5);
        for (std::size_t k = 0; k < h.v.size(); ++k) {
            h.v[k] = depth(rng);
            u.v[k] = speed(rng);
            v.v[k] = cross(rng);
            hu.v[k] = h.v[k] * u.v[k];
            hv.v[k] = h.v[k] * v.v[k];
            c.v[k] = coef(rng);
            a.v[k] = std::sqrt(c.v[k] * h.v[k]);
            px.v[k] = py.v[k] = gn.v[k] = 9.0;
            nt.v[k] = 1.0;
            sx.v[k] = slope(rng);
            sy.v[k] = slope(rng);
            ax.v[k] = 3.0;
            ay.v[k] = 1.0;
            elevation.v[k] = 100.0;
        }
    }
    // The x-faces of the middle row, with the per-cell quotients and celerities the
    // flux kernels read.
    FaceRowInput x_faces() {
        FaceRowInput in{h.mid(), hu.mid(), hv.mid(), c.mid(), 1};
        in.un = u.mid();
        in.ut = v.mid();
        in.a = a.mid();
        return in;
    }
};

template <class Kernel>
void run_per_item(benchmark::State& state, int items, Kernel&& kernel) {
    for (auto _ : state) {
        kernel();
        benchmark::ClobberMemory();
    }
    // Seconds per face or cell (printed with an SI prefix: "9.4n" is 9.4 ns); a time,
    // so the "min" aggregate over repetitions is the least disturbed one.
    state.counters["per_item"] = benchmark::Counter(
        items, benchmark::Counter::kIsIterationInvariantRate | benchmark::Counter::kInvert);
}

// ---------------------------------------------------------------- faces

void bm_waf_face_row(benchmark::State& state) {
    Layer w;
    Rows oh, oq, ot;
    const FaceRowInput in = w.x_faces();
    const FaceRowOutput out{oh.mid(), oq.mid(), ot.mid()};
    run_per_item(state, kRow, [&] { waf_face_row(in, out, kRow, 1e-3, 0.01, Limiter::van_leer); });
    state.SetLabel("per face, van Leer, no front");
}
BENCHMARK(bm_waf_face_row)->ComputeStatistics("min", min_of);

void bm_hllc_face_row(benchmark::State& state) {
    Layer w;
    Rows oh, oq, ot;
    const FaceRowInput in = w.x_faces();
    const FaceRowOutput out{oh.mid(), oq.mid(), ot.mid()};
    run_per_item(state, kRow, [&] { hllc_face_row(in, out, kRow, 1e-3); });
    state.SetLabel("per face");
}
BENCHMARK(bm_hllc_face_row)->ComputeStatistics("min", min_of);

void bm_predictor_row(benchmark::State& state) {
    Layer w;
    Rows fh, fq, ft, ph, pq, pt, pu, pv;
    for (Rows* r : {&fh, &fq, &ft}) std::fill(r->v.begin(), r->v.end(), 0.1);
    const FaceRowInput q = w.x_faces();
    const FaceRowOutput flux{fh.mid(), fq.mid(), ft.mid()};
    FaceRowOutput out{ph.mid(), pq.mid(), pt.mid()};
    out.un = pu.mid();
    out.ut = pv.mid();
    run_per_item(state, kRow, [&] { predictor_row(q, flux, 0.01, 1e-3, out, kRow); });
    state.SetLabel("per cell");
}
BENCHMARK(bm_predictor_row)->ComputeStatistics("min", min_of);

void bm_celerity_row(benchmark::State& state) {
    Layer w;
    Rows a;
    run_per_item(state, kRow, [&] { celerity_row(w.h.mid(), w.c.mid(), 1e-3, a.mid(), kRow); });
    state.SetLabel("per cell");
}
BENCHMARK(bm_celerity_row)->ComputeStatistics("min", min_of);

// ---------------------------------------------------------------- cells

void bm_state_velocity_row(benchmark::State& state) {
    Layer w;
    Rows u, v;
    run_per_item(state, kRow, [&] {
        state_velocity_row(w.h.mid(), w.hu.mid(), w.hv.mid(), u.mid(), v.mid(), 0, kRow);
    });
    state.SetLabel("per cell");
}
BENCHMARK(bm_state_velocity_row)->ComputeStatistics("min", min_of);

// Argument 1: the first-order scheme's rule (a compression confirmed at both scales).
void bm_regime_row(benchmark::State& state) {
    Layer w;
    std::vector<RegimeFlags> regime(static_cast<std::size_t>(kRow + 2 * kPad), kRegimeAtStart);
    RegimeRowInput in{w.h.mid(),  w.hu.mid(),  w.hv.mid(),  w.h.at(-1), w.hv.at(-1),
                      w.h.at(1),  w.hv.at(1),  w.h.at(-1),  w.hv.at(-1), w.h.at(1),
                      w.hv.at(1)};  // rows -/+ 2 stand in as -/+ 1
    in.confirm_at_both_scales = state.range(0) != 0;
    run_per_item(state, kRow, [&] {
        regime_row(in, regime.data() + kPad, 1e-3, 0.05, 0, kRow, -kPad, kRow + kPad - 1);
    });
    state.SetLabel(in.confirm_at_both_scales ? "per cell, both scales" : "per cell");
}
BENCHMARK(bm_regime_row)->Arg(0)->Arg(1)->ComputeStatistics("min", min_of);

// The regime stage as the stepper runs it, per row: the terms of one new row and the
// regimes from the terms (the rows around it computed once, as the stepper keeps them),
// in the DEM frame. First argument: 1 for the first-order scheme's rule. Second: 0 the
// layer's random velocities (some blocks of cells decided by their central differences
// alone, most not), 1 a flow whose velocity falls in x from cell to cell (every cell
// compresses: no block decided), 2 a uniform flow (every block decided, as on case (a)).
void bm_regime_stage(benchmark::State& state) {
    Layer w;
    for (int r = -1; r <= 1; ++r)
        for (int i = -kPad; i < kRow + kPad; ++i) {
            if (state.range(1) == 1) w.hu.at(r)[i] = w.h.at(r)[i] * (20.0 - 0.01 * i);
            if (state.range(1) == 2) {
                w.hu.at(r)[i] = w.h.at(r)[i] * 5.0;
                w.hv.at(r)[i] = w.h.at(r)[i] * 1.0;
            }
        }
    std::vector<RegimeFlags> regime(static_cast<std::size_t>(kRow + 2 * kPad), kRegimeAtStart);
    RegimeRowInput in{w.h.mid(),  w.hu.mid(),  w.hv.mid(),  w.h.at(-1), w.hv.at(-1),
                      w.h.at(1),  w.hv.at(1),  w.h.at(-1),  w.hv.at(-1), w.h.at(1),
                      w.hv.at(1)};  // rows -/+ 2 stand in as -/+ 1
    in.sx = w.sx.mid();
    in.sy = w.sy.mid();
    in.sy_s = in.sy_ss = w.sy.at(-1);
    in.sy_n = in.sy_nn = w.sy.at(1);
    in.confirm_at_both_scales = state.range(0) != 0;
    Rows wet, still_x, still_y, scratch;
    const double h_min = 1e-3, rest = 0.05;
    for (int r = -1; r <= 1; ++r)
        regime_terms_row(w.h.at(r), w.hu.at(r), w.hv.at(r), w.sx.at(r), w.sy.at(r), h_min, rest,
                         {wet.at(r), still_x.at(r), still_y.at(r)}, -2, kRow + 2);
    const RegimeRowTerms t{wet.mid(),      wet.at(-1),     wet.at(1),     wet.at(-1),
                           wet.at(1),      still_x.mid(),  still_y.mid(), still_y.at(-1),
                           still_y.at(1),  still_y.at(-1), still_y.at(1)};
    run_per_item(state, kRow, [&] {
        // The new row's terms (written to scratch rows nothing reads).
        regime_terms_row(w.h.at(1), w.hu.at(1), w.hv.at(1), w.sx.at(1), w.sy.at(1), h_min, rest,
                         {scratch.at(-1), scratch.at(0), scratch.at(1)}, -2, kRow + 2);
        regime_row_from_terms(in, t, regime.data() + kPad, 0, kRow, -kPad, kRow + kPad - 1);
    });
    state.SetLabel(std::string("per cell, DEM frame") + (in.confirm_at_both_scales ? ", both scales" : "") +
                   (state.range(1) == 0 ? ", random velocities"
                    : state.range(1) == 1 ? ", compressing"
                                          : ", uniform flow"));
}
BENCHMARK(bm_regime_stage)->Args({0, 0})->Args({1, 0})->Args({0, 1})->Args({0, 2})->ComputeStatistics("min", min_of);

void bm_pressure_row(benchmark::State& state) {
    Layer w;
    Rows cx, cy, ulo, uhi, vlo, vhi, shi, ax, ay;
    std::vector<RegimeFlags> regime(static_cast<std::size_t>(kRow + 2 * kPad));
    for (std::size_t i = 0; i < regime.size(); ++i) regime[i] = static_cast<RegimeFlags>(i % 4);
    const PressureRowInput in{w.h.mid(),  w.u.mid(),  w.v.mid(),  w.px.mid(),
                              w.py.mid(), w.gn.mid(), w.nt.mid(), w.sx.mid(),
                              w.sy.mid(), regime.data() + kPad};
    const PressureRowOutput out{cx.mid(),  cy.mid(),  ulo.mid(), uhi.mid(), vlo.mid(),
                                vhi.mid(), shi.mid(), ax.mid(),  ay.mid()};
    const MaterialParams m;
    const EarthPressureCoefficients k = earth_pressure_coefficients(m);
    const PressureRowParams p{k, std::max(k.kx_active, k.kx_passive), 1e-3, false};
    run_per_item(state, kRow, [&] { pressure_row(in, out, p, 0, kRow); });
    state.SetLabel("per cell, Savage-Hutter, DEM frame");
}
BENCHMARK(bm_pressure_row)->ComputeStatistics("min", min_of);

// Face fluxes small enough that no cell is emptied and no velocity leaves its bounds:
// the vector path of the donor factors and the update, none of the scalar fix-ups.
struct Fluxes {
    Rows fxh, fxu, fxv, fyh, fyu, fyv, factor, ulo, uhi, vlo, vhi, shi;
    Fluxes() {
        std::mt19937_64 rng(7);
        std::uniform_real_distribution<double> f(-0.5, 0.5);
        for (Rows* r : {&fxh, &fxu, &fxv, &fyh, &fyu, &fyv})
            for (double& x : r->v) x = f(rng);
        std::fill(factor.v.begin(), factor.v.end(), 1.0);
        std::fill(ulo.v.begin(), ulo.v.end(), -100.0);
        std::fill(uhi.v.begin(), uhi.v.end(), 100.0);
        std::fill(vlo.v.begin(), vlo.v.end(), -100.0);
        std::fill(vhi.v.begin(), vhi.v.end(), 100.0);
        std::fill(shi.v.begin(), shi.v.end(), 200.0);
    }
    FaceFluxRows rows() {
        return {fxh.mid(), fxu.mid(), fxv.mid(), fyh.mid(), fyu.mid(), fyv.mid()};
    }
};

void bm_donor_factor_row(benchmark::State& state) {
    Layer w;
    Fluxes f;
    Rows factor;
    run_per_item(state, kRow, [&] {
        donor_factor_row(f.rows(), w.h.mid(), 0.01, 0.01, 1e-3, kStride, factor.mid(), 0, kRow);
    });
    state.SetLabel("per cell");
}
BENCHMARK(bm_donor_factor_row)->ComputeStatistics("min", min_of);

void bm_update_row(benchmark::State& state) {
    Layer w;
    Fluxes f;
    Rows nh, nhu, nhv;
    const UpdateRowInput in{f.rows(),    f.factor.mid(), f.ulo.mid(),       f.uhi.mid(),
                            f.vlo.mid(), f.vhi.mid(),    f.shi.mid(),       w.h.mid(),
                            w.hu.mid(),  w.hv.mid(),     w.elevation.mid(), w.sx.mid(),
                            w.sy.mid()};
    const UpdateRowParams p{0.01, 0.01, kStride, std::numeric_limits<double>::infinity(), 9.81};
    run_per_item(state, kRow, [&] { update_row(in, p, nh.mid(), nhu.mid(), nhv.mid(), 0, kRow); });
    state.SetLabel("per cell, DEM frame");
}
BENCHMARK(bm_update_row)->ComputeStatistics("min", min_of);

// One half step of the sources; the state is restored from a copy each time (the copy
// is timed too: three row copies, a small part of the cost).
void bm_sources_row(benchmark::State& state) {
    Layer w;
    const Layer start;
    const SourceRowTerrain t{w.ax.mid(), w.ay.mid(), w.gn.mid(), w.elevation.mid(), nullptr,
                             nullptr,    nullptr,    w.sx.mid(), w.sy.mid()};
    const SourceRowParams p{1e-3, 1, std::tan(0.35), 9.81, 1e9};
    run_per_item(state, kRow, [&] {
        w.hu.v = start.hu.v;
        w.hv.v = start.hv.v;
        apply_sources_row(w.h.mid(), w.hu.mid(), w.hv.mid(), t, p, 0, kRow);
    });
    state.SetLabel("per cell, DEM frame, incl. restoring the row");
}
BENCHMARK(bm_sources_row)->ComputeStatistics("min", min_of);

void bm_cfl_rate_row(benchmark::State& state) {
    Layer w;
    run_per_item(state, kRow, [&] {
        double r = cfl_rate_row(w.h.mid(), w.hu.mid(), w.hv.mid(),
                                CflRowTerrain{nullptr, nullptr, w.sx.mid(), w.sy.mid(), 9.81}, 1.2,
                                0.8, 5.0, 5.0, 1e-3, 0, kRow);
        benchmark::DoNotOptimize(r);
    });
    state.SetLabel("per cell, DEM frame");
}
BENCHMARK(bm_cfl_rate_row)->ComputeStatistics("min", min_of);

}  // namespace

BENCHMARK_MAIN();
