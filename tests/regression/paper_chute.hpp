#pragma once
// One chute run of the validation study (docs/validation.md) reduced to the numbers the
// paper discusses: the final deposit along the centre line (Wang & Li 2017 Figs. 2, 3),
// the runout metrics of the products (Fig. 5, runout efficiency), and the front and tail
// of the flow at given times (Koch et al. 1994, Wang & Li Fig. 6). Shared by the fast
// test (test_paper_parametric.cpp) and tools/validation_study.cpp, so that the test
// asserts exactly what the report plots, only on a coarser grid.
//
// Front and tail: along the centre line y = width/2 (the mean of the two middle rows
// when ny is even, i.e. the value interpolated at the centre line), the largest and the
// smallest bed coordinate x where the bed-normal depth reaches `front_threshold`,
// interpolated linearly between cell centres.
#include <string>
#include <vector>

#include "avalanche/core/simulation.hpp"
#include "avalanche/numerics/parameters.hpp"
#include "avalanche/output/runout.hpp"
#include "avalanche/physics/chute.hpp"
#include "avalanche/physics/material.hpp"
#include "avalanche/physics/release.hpp"

namespace avalanche::validation {

struct ChuteCase {
    ChuteGeometry geometry;
    CapRelease cap;
    MaterialParams material;
    NumericsParams numerics;
    double cell_size = 0.5;          // m
    double front_threshold = 0.01;   // m, bed-normal: what counts as "flow" for front/tail
    std::vector<double> probe_times; // s: front/tail recorded at these times
};

// Front and tail along the centre line at one time; found = some cell reaches the
// threshold.
struct FrontTail {
    double t = 0.0;
    double front = 0.0, tail = 0.0;  // m along the bed
    double max_depth = 0.0;          // m, bed-normal, centre line
    bool found = false;
};

struct ChuteOutcome {
    RunStatistics stats;
    RunoutMetrics runout;             // as in summary.json (h_thr = front_threshold)
    std::vector<double> x;            // bed coordinate of the cell centres (m)
    std::vector<double> deposit;      // final bed-normal depth on the centre line (m)
    FrontTail deposit_extent;         // front/tail of `deposit` at the end
    double deposit_max_depth = 0.0;   // m, anywhere
    double deposit_width = 0.0;       // m: lateral extent of cells with final depth >= threshold
    double toe_x = 0.0;               // m along the bed: end of the transition (start of the runout)
    std::vector<FrontTail> probes;    // one per probe time (t = the time actually recorded)
};

// Runs the case on one thread (the caller's OpenMP setting) and reduces it.
ChuteOutcome run_chute_case(const ChuteCase& c);

// Front/tail of a centre-line profile.
FrontTail front_tail(const std::vector<double>& x, const std::vector<double>& h,
                     double threshold);

// The parametric chute of Wang & Li (2017) section 2.3 as shipped in
// scenarios/paper_slope<N>/scenario.toml (the test builds it without the TOML reader):
// plane at `slope_deg`, transition 25-30 m, 120 m runout, 60 m wide, cap R = 2.5 m at
// (7.5, 30) m.
ChuteCase paper_chute(double slope_deg, double delta_deg, double phi_deg, double cell_size);

}  // namespace avalanche::validation
