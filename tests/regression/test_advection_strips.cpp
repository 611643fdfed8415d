// The advection runs strip by strip (advection.cpp): each thread takes consecutive
// strips, carries the rows a strip shares with the next, and recomputes them at the
// start of its block. The result must not depend on how the rows are shared out:
// one thread (every strip but the first carried) and two threads (each block starting
// afresh) must give the same bits, with walls and with open edges, for both schemes,
// on a flow with wet/dry fronts, outflow and cells of every kind. A strip writes its
// updated rows into the state at once unless it borders another thread's block (those
// wait until every block is done): 3 and 7 threads on the 9 strips of the box give
// blocks of three, two and one strips, where most or all strips wait.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>

#include "avalanche/numerics/stepper.hpp"
#include "support/analytic_harness.hpp"

using namespace avalanche;

namespace {

struct Result {
    State state;
    double outflow = 0.0;
};

// 220 x 130 cells (above the stepper's threading threshold): a wavy dam holding 2 m
// over a 0.2 m layer, dry ground beyond x = 180 m, on a 10 deg plane, 10 steps.
Result run(Scheme scheme, Boundary boundary, int threads) {
    const analytic::ScopedThreads scoped(threads);
    const Grid g = analytic::box_grid(0.0, 220.0, 0.0, 130.0, 1.0);
    const TerrainFields t = analytic::plane_terrain(g, 10.0, 9.81);
    State s = analytic::make_state(
        g,
        [](double xa, double xb, double ya, double yb) {
            const double x = 0.5 * (xa + xb), y = 0.5 * (ya + yb);
            if (x > 180.0) return 0.0;
            return x < 100.0 + 20.0 * std::sin(y / 15.0) ? 2.0 : 0.2;
        },
        [](double x, double y) {
            return std::pair<double, double>{2.0 + 0.01 * x, std::sin(y / 10.0)};
        });
    MaterialParams m;
    NumericsParams n;
    n.scheme = scheme;
    n.boundary = boundary;
    Stepper stepper(g, t, m, n, 1e-4);
    stepper.reset_active_box(s);
    for (int step = 0; step < 10; ++step) stepper.step(s, 0.5 * stepper.stable_dt(s));
    return {s, stepper.outflow_volume()};
}

bool same_bits(const Field2D& a, const Field2D& b) {
    return a.raw().size() == b.raw().size() &&
           std::memcmp(a.raw().data(), b.raw().data(), a.raw().size() * sizeof(double)) == 0;
}

}  // namespace

TEST(AdvectionStrips, OneAndTwoThreadsGiveTheSameBits) {
    for (const Scheme scheme : {Scheme::waf, Scheme::godunov}) {
        for (const Boundary boundary : {Boundary::open, Boundary::wall}) {
            const Result one = run(scheme, boundary, 1);
            for (const int threads : {2, 3, 7}) {
                const Result many = run(scheme, boundary, threads);
                EXPECT_TRUE(same_bits(one.state.h, many.state.h) &&
                            same_bits(one.state.hu, many.state.hu) &&
                            same_bits(one.state.hv, many.state.hv))
                    << "scheme " << static_cast<int>(scheme) << " boundary "
                    << static_cast<int>(boundary) << " threads " << threads;
                EXPECT_EQ(one.outflow, many.outflow);
            }
            // The flow moved and, with open edges, left the domain: the comparison
            // covered the update, the fronts and the edge faces.
            EXPECT_GT(one.state.h.raw().size(), 0u);
            if (boundary == Boundary::open) {
                EXPECT_GT(one.outflow, 0.0);
            }
        }
    }
}
