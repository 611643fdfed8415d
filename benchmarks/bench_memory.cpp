// The machine's streaming bandwidth over grid-sized fields: what the solver's per-cell
// passes could move at best (docs/performance.md, "Where the targets stand").
//
// bm_grid_stream/R/W reads R fields and writes W fields of kCells doubles each (case (a)'s
// 1000 x 1000 grid, 8 MB a field), cell by cell in one vector loop, as a per-cell pass
// of the time loop does (the sources pass reads h, hu, hv, sx, sy and writes h, hu, hv:
// 5/3), on 1 or 2 OpenMP threads (the argument), each over its half of the cells, as the
// solver's passes split the rows.
// Case (a)'s state and terrain (h, hu, hv, sx, sy, elevation: 48 MB) do not fit the
// last-level cache (32 MiB on the project machine); the fields of one pass may in part
// (a copy's 16 MB do), as in the solver: the figures are what such a pass costs here from
// memory and the last-level cache together. Counters: bytes_per_second (read and
// written), per_cell (seconds per cell of the pass, all threads together).
//
//   bench_memory --benchmark_repetitions=5 --benchmark_report_aggregates_only=true
//
// Read the time and per_cell of the "min" rows; their bytes_per_second is the smallest
// rate, that is the slowest repetition's.
#include <benchmark/benchmark.h>

#include <array>
#include <cstdint>
#include <cstddef>
#include <vector>

#include <omp.h>

#include "min_statistic.hpp"

namespace {

using avalanche::bench::min_of;

constexpr std::size_t kCells = 1000 * 1000;

// The fields of one benchmark, shared by its OpenMP threads (each writes only its share).
struct Fields {
    std::vector<std::vector<double>> in, out;
    Fields(int reads, int writes)
        : in(static_cast<std::size_t>(reads), std::vector<double>(kCells, 1.0)),
          out(static_cast<std::size_t>(writes), std::vector<double>(kCells, 0.0)) {}
};

// One pass over cells [c0, c1): every written field gets the sum of the read fields
// times a factor of its own, so no read can be skipped and no two writes are the same;
// the sum of the sums is returned, so that a pass that writes nothing is not skipped.
template <int R, int W>
double pass(Fields& f, std::size_t c0, std::size_t c1) {
    std::array<const double*, R> in;
    std::array<double*, W> out;
    for (std::size_t r = 0; r < in.size(); ++r) in[r] = f.in[r].data();
    for (std::size_t w = 0; w < out.size(); ++w) out[w] = f.out[w].data();
    double total = 0.0;
#pragma omp simd reduction(+ : total)
    for (std::size_t c = c0; c < c1; ++c) {
        double s = 0.0;
        for (int r = 0; r < R; ++r) s += in[static_cast<std::size_t>(r)][c];
        for (int w = 0; w < W; ++w) out[static_cast<std::size_t>(w)][c] = s * (1.0 + w);
        total += s;
    }
    return total;
}

// The pass on state.range(0) OpenMP threads, each over its contiguous share of the cells,
// as the time loop's per-cell passes split the rows (schedule static).
template <int R, int W>
void bm_grid_stream(benchmark::State& state) {
    const int threads = static_cast<int>(state.range(0));
    Fields fields(R, W);
    for (auto _ : state) {
        double total = 0.0;
#pragma omp parallel num_threads(threads) reduction(+ : total)
        {
            const auto n = static_cast<std::size_t>(omp_get_num_threads());
            const auto t = static_cast<std::size_t>(omp_get_thread_num());
            total += pass<R, W>(fields, kCells * t / n, kCells * (t + 1) / n);
        }
        benchmark::DoNotOptimize(total);
    }
    const auto cells = static_cast<double>(state.iterations()) * static_cast<double>(kCells);
    state.SetBytesProcessed(static_cast<std::int64_t>(cells * (R + W) * sizeof(double)));
    state.counters["per_cell"] =
        benchmark::Counter(cells, benchmark::Counter::kIsRate | benchmark::Counter::kInvert);
}

// The time loop's passes by the grid fields they read and write: the CFL rate (h, hu, hv,
// sx, sy: 5, 0), the state check (3, 0), the sources (5, 3), an advection (h, hu, hv,
// sx, sy, elevation; h, hu, hv: 6, 3), and a copy (1, 1).
BENCHMARK(bm_grid_stream<3, 0>)->Arg(1)->Arg(2)->UseRealTime()->ComputeStatistics("min", min_of);
BENCHMARK(bm_grid_stream<5, 0>)->Arg(1)->Arg(2)->UseRealTime()->ComputeStatistics("min", min_of);
BENCHMARK(bm_grid_stream<5, 3>)->Arg(1)->Arg(2)->UseRealTime()->ComputeStatistics("min", min_of);
BENCHMARK(bm_grid_stream<6, 3>)->Arg(1)->Arg(2)->UseRealTime()->ComputeStatistics("min", min_of);
BENCHMARK(bm_grid_stream<1, 1>)->Arg(1)->Arg(2)->UseRealTime()->ComputeStatistics("min", min_of);

}  // namespace

BENCHMARK_MAIN();
