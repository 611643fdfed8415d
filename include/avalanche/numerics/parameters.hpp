#pragma once
// Numerical parameters with their defaults and units in one place (STYLE.md 5).
// Validated once by validate(); kernels never see literal tolerances.

namespace avalanche {

enum class Scheme {
    waf,      // second-order WAF-TVD with HLLC (Wang & Li 2017 eqs. 6-10); default
    godunov,  // first-order Godunov with HLLC: the fast, diffusive option
};

enum class Limiter { superbee, van_leer, van_albada, minmod };

enum class Boundary {
    open,  // transmissive, outflow counted, no inflow
    wall,  // solid reflecting wall
};

enum class Splitting {
    lsl,  // L(dt/2) S(dt) L(dt/2): Wang & Li (2017) eq. 12, the default
    sls,  // S(dt/2) L(dt) S(dt/2): also Strang, half the flux work per step
};

struct NumericsParams {
    Scheme scheme = Scheme::waf;
    Limiter limiter = Limiter::van_leer;  // smooth and symmetric; superbee sharpens fronts more
    Splitting splitting = Splitting::lsl;
    double cfl = 0.2;            // Courant number (paper: 0.2), at most 0.5 (paper eq. 11)
    double h_min = 0.0;          // thin-layer depth (m); 0 = automatic: h_min_relative * max release
    double h_min_relative = 1e-5;
    int source_substeps = 1;     // m in paper eq. 12
    // Faces between cells friction holds at rest pass no mass while the static driving
    // across them stays below the Coulomb limit (rest_faces.hpp; MODEL.md 2.4).
    bool rest_faces = false;
    Boundary boundary = Boundary::open;
    double t_end = 300.0;        // s, hard end of the simulation
    double output_interval = 1.0;  // s between snapshots
    double stop_ke_fraction = 1e-4;  // flow stopped when KE < fraction * max KE ...
    double stop_duration = 1.0;      // ... continuously for this long (s)
    int active_margin = 4;       // cells added around the wet area each step
    double gravity = 9.81;       // m/s^2
};

void validate(const NumericsParams& n);

// The Courant number of each advection: the step's for S L S, half of it for L S L,
// which advects twice per step over half the step.
double advection_courant(const NumericsParams& n);

}  // namespace avalanche
