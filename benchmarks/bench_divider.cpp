// Throughput of double-precision division and square root against multiplication,
// with 2-, 4- and 8-wide vectors (docs/performance.md, "What limits it now: the
// divider"): the WAF step needs ~84 divisions and ~34 square roots per cell update,
// and on this machine wider vectors do not divide faster, so those set its bound.
// Each benchmark runs an independent operation over L1-resident arrays of 1024 doubles.
#include <benchmark/benchmark.h>

#include <cmath>
#include <vector>

namespace {

constexpr int kN = 1024;

struct Arrays {
    std::vector<double> a, b, c;
    Arrays() : a(kN), b(kN), c(kN) {
        for (int i = 0; i < kN; ++i) {
            a[i] = 1.0 + i;
            b[i] = 3.0 + 0.5 * i;
        }
    }
};

#define AVALANCHE_KERNELS(suffix, target)                                        \
    target void divide_##suffix(const double* a, const double* b, double* c) {   \
        _Pragma("omp simd") for (int i = 0; i < kN; ++i) c[i] = a[i] / b[i];     \
    }                                                                            \
    target void root_##suffix(const double* a, const double*, double* c) {       \
        _Pragma("omp simd") for (int i = 0; i < kN; ++i) c[i] = std::sqrt(a[i]); \
    }                                                                            \
    target void multiply_##suffix(const double* a, const double* b, double* c) { \
        _Pragma("omp simd") for (int i = 0; i < kN; ++i) c[i] = a[i] * b[i];     \
    }

#if defined(__GNUC__) && defined(__x86_64__)
AVALANCHE_KERNELS(sse2, __attribute__((noinline)))
AVALANCHE_KERNELS(avx2, __attribute__((noinline, target("avx2"))))
AVALANCHE_KERNELS(avx512, __attribute__((noinline, target("avx512f,prefer-vector-width=512"))))
#else
AVALANCHE_KERNELS(sse2, )
#endif

using Kernel = void (*)(const double*, const double*, double*);

enum class Isa { sse2, avx2, avx512 };

bool available(Isa isa) {
#if defined(__GNUC__) && defined(__x86_64__)
    switch (isa) {
        case Isa::sse2:
            return true;
        case Isa::avx2:
            return __builtin_cpu_supports("avx2");
        case Isa::avx512:
            return __builtin_cpu_supports("avx512f");
    }
#endif
    return isa == Isa::sse2;
}

void run(benchmark::State& state, Kernel k, Isa isa) {
    if (!available(isa)) {
        state.SkipWithError("instruction set not available");
        return;
    }
    Arrays x;
    for (auto _ : state) {
        k(x.a.data(), x.b.data(), x.c.data());
        benchmark::DoNotOptimize(x.c.data());
        benchmark::ClobberMemory();
    }
    state.SetItemsProcessed(state.iterations() * kN);
}

}  // namespace

BENCHMARK_CAPTURE(run, divide_sse2, divide_sse2, Isa::sse2);
BENCHMARK_CAPTURE(run, root_sse2, root_sse2, Isa::sse2);
BENCHMARK_CAPTURE(run, multiply_sse2, multiply_sse2, Isa::sse2);
#if defined(__GNUC__) && defined(__x86_64__)
BENCHMARK_CAPTURE(run, divide_avx2, divide_avx2, Isa::avx2);
BENCHMARK_CAPTURE(run, root_avx2, root_avx2, Isa::avx2);
BENCHMARK_CAPTURE(run, multiply_avx2, multiply_avx2, Isa::avx2);
BENCHMARK_CAPTURE(run, divide_avx512, divide_avx512, Isa::avx512);
BENCHMARK_CAPTURE(run, root_avx512, root_avx512, Isa::avx512);
BENCHMARK_CAPTURE(run, multiply_avx512, multiply_avx512, Isa::avx512);
#endif

BENCHMARK_MAIN();
