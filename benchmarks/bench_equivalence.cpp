// Bitwise fingerprints of the solver: FNV-1a hashes of h, hu, hv (ghost cells
// included, row by row), the outflow volume and the cell-update count after a fixed number of
// steps, for a matrix of scenes and options (schemes, limiters, walls, splittings,
// isotropic pressure, DEM and chute frames, one and two threads above the threading
// threshold). A change that must not change results prints the same lines before and
// after: build this tool on both trees and diff the outputs.
//
//   bench_equivalence [--threads N] [--strip-rows S]
//
// --strip-rows fixes every band's strips at S rows (1 to 16; Stepper::set_strip_rows),
// which must not change a line either.
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <functional>
#include <string>
#include <vector>

#ifdef _OPENMP
#include <omp.h>
#endif

#include "avalanche/numerics/stepper.hpp"
#include "bench_scenes.hpp"

using namespace avalanche;
using namespace avalanche::bench;

namespace {

struct Fnv {
    std::uint64_t h = 1469598103934665603ULL;
    void add(const void* p, std::size_t n) {
        const auto* b = static_cast<const unsigned char*>(p);
        for (std::size_t k = 0; k < n; ++k) {
            h ^= b[k];
            h *= 1099511628211ULL;
        }
    }
    // Every cell, ghosts included, row by row (whatever the storage's row padding).
    void add(const Field2D& f) {
        const int ng = f.ghosts();
        for (int j = -ng; j < f.ny() + ng; ++j)
            add(f.row(j) - ng, static_cast<std::size_t>(f.nx() + 2 * ng) * sizeof(double));
    }
    void add(double x) { add(&x, sizeof x); }
};

struct Case {
    std::string name;
    std::function<Scene()> build;
    std::function<void(Scene&)> tweak;
    int steps;
};

void run(const Case& c, int strip_rows) {
    Scene s = c.build();
    c.tweak(s);
    Stepper st(s.grid, s.terrain, s.material, s.numerics, s.h_min);
    st.set_strip_rows(strip_rows);
    State state = s.initial;
    st.reset_active_box(state);
    int steps = 0;
    for (; steps < c.steps; ++steps) {
        const double dt = st.stable_dt(state);
        if (!std::isfinite(dt)) break;
        st.step(state, dt);
    }
    Fnv f;
    f.add(state.h);
    f.add(state.hu);
    f.add(state.hv);
    f.add(st.outflow_volume());
    f.add(st.energy_budget());
    const std::uint64_t updates = st.cell_updates();
    f.add(&updates, sizeof updates);
    std::printf("%-32s %4d steps  %016llx\n", c.name.c_str(), steps,
                static_cast<unsigned long long>(f.h));
}

}  // namespace

int main(int argc, char** argv) {
    int strip_rows = 0;  // by the bands' widths
    for (int a = 1; a < argc; a += 2) {
        if (a + 1 == argc) {
            std::fprintf(stderr, "bench_equivalence: option %s needs a value\n", argv[a]);
            return 2;
        }
        if (std::strcmp(argv[a], "--threads") == 0) {
#ifdef _OPENMP
            omp_set_num_threads(std::atoi(argv[a + 1]));
#endif
        } else if (std::strcmp(argv[a], "--strip-rows") == 0) {
            strip_rows = std::atoi(argv[a + 1]);
        } else {
            std::fprintf(stderr, "bench_equivalence: unknown option %s\n", argv[a]);
            return 2;
        }
    }
    const auto none = [](Scene&) {};
    const auto wall_minmod = [](Scene& s) {
        s.numerics.boundary = Boundary::wall;
        s.numerics.limiter = Limiter::minmod;
    };
    const auto superbee_sls = [](Scene& s) {
        s.numerics.limiter = Limiter::superbee;
        s.numerics.splitting = Splitting::sls;
    };
    const auto isotropic = [](Scene& s) {
        s.material.earth_pressure = EarthPressureModel::isotropic;
    };
    const ValleyRelease release{0.0, 9000.0, 200.0, 20.0};
    std::vector<Case> cases;
    for (Scheme scheme : {Scheme::waf, Scheme::godunov}) {
        const std::string sch = to_string(scheme);
        const auto plane = [=](int n) {
            return [=] { return tilted_plane(n, 5.0, 30.0, 1.0, scheme); };
        };
        const auto chute = [=] { return paper_chute(0.5, scheme); };
        const auto vall = [=] {
            return valley(160, 260, 10.0, -800.0, 7000.0, release, scheme, 1e6);
        };
        cases.push_back({"plane120_" + sch, plane(120), none, 40});
        cases.push_back({"plane300_" + sch, plane(300), none, 8});  // threaded above 20000 cells
        cases.push_back({"chute_" + sch, chute, none, 400});
        cases.push_back({"chute_wall_minmod_" + sch, chute, wall_minmod, 400});
        cases.push_back({"chute_superbee_sls_" + sch, chute, superbee_sls, 300});
        cases.push_back({"chute_isotropic_" + sch, chute, isotropic, 300});
        cases.push_back({"valley_" + sch, vall, none, 300});
        cases.push_back({"valley_superbee_sls_" + sch, vall, superbee_sls, 200});
        cases.push_back({"valley_isotropic_wall_" + sch, vall,
                         [](Scene& s) {
                             s.material.earth_pressure = EarthPressureModel::isotropic;
                             s.numerics.boundary = Boundary::wall;
                         },
                         200});
    }
    for (const Case& c : cases) run(c, strip_rows);
    return 0;
}
