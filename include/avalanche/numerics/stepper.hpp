#pragma once
// One time step of the Savage–Hutter solver: Strang splitting of advection L and
// point-wise sources S (Wang & Li 2017 eq. 12), with
//  - L: unsplit WAF-TVD fluxes on states advanced half a step by a transverse
//    first-order Godunov predictor (eqs. 6-9), or the first-order HLLC Godunov flux;
//  - the thin-layer wet/dry rule (section 2.2.3): cells thinner than h_min do not
//    export mass, take the velocity of their deepest wet neighbour, or stop;
//  - a conservative positivity limiter that scales the outgoing face fluxes of a
//    cell that would otherwise be emptied below zero;
//  - S: tangential gravity, then Coulomb friction as a stopping magnitude.
// The state's ghost cells are filled here from the boundary conditions.
#include <array>
#include <cstdint>

#include "avalanche/core/grid.hpp"
#include "avalanche/core/state.hpp"
#include "avalanche/numerics/active_box.hpp"
#include "avalanche/numerics/parameters.hpp"
#include "avalanche/physics/earth_pressure.hpp"
#include "avalanche/physics/material.hpp"
#include "avalanche/physics/terrain.hpp"

namespace avalanche {

class Stepper {
public:
    Stepper(const Grid& grid, const TerrainFields& terrain, const MaterialParams& material,
            const NumericsParams& numerics, double h_min);

    // Largest stable step for the current state: C * min(dx / max(|u| + a_x), dy / max(|v| + a_y))
    // over the wet cells; +infinity when nothing is wet.
    [[nodiscard]] double stable_dt(const State& s) const;

    // Advances the state by dt over the active box (recomputed from the state).
    void step(State& s, double dt);

    // Recomputes the active box from scratch (after the state was set from outside).
    void reset_active_box(const State& s);

    [[nodiscard]] const ActiveBox& active_box() const { return box_; }
    [[nodiscard]] double h_min() const { return h_min_; }
    // Volume that left the domain through open edges since construction (m^3).
    [[nodiscard]] double outflow_volume() const { return outflow_volume_; }
    void set_outflow_volume(double v) { outflow_volume_ = v; }
    // Number of cell updates performed (active cells x steps).
    [[nodiscard]] std::uint64_t cell_updates() const { return cell_updates_; }

    // The operators, public for tests of the splitting.
    void advect(State& s, double tau);
    void apply_sources(State& s, double dt) const;
    void fill_ghosts(State& s) const;

private:
    void update_pressure_coefficients(const State& s);
    void godunov_predictor(const State& s, double tau, bool along_x);
    void face_fluxes(const State& s, const State& predicted, double tau, bool along_x, bool waf);
    void fix_boundary_faces(const State& s);
    void limit_and_update(State& s, double tau);
    void thin_layer_velocities(State& s) const;
    void shrink_box_to_wet(const State& s, const ActiveBox& search);

    Grid grid_;
    const TerrainFields& terrain_;
    MaterialParams material_;
    NumericsParams numerics_;
    EarthPressureCoefficients k_;
    double tan_delta_;
    double h_min_;

    ActiveBox box_;       // cells updated this step
    ActiveBox wet_box_;   // bounding box of cells with h > 0
    Field2D cx_, cy_;     // k_x p_x and k_y p_y per cell
    State pred_x_, pred_y_;  // states advanced by the transverse predictors
    State flux_x_, flux_y_;  // face fluxes; flux_x_(i, j) is the face left of cell i
    Field2D donor_factor_;   // positivity scaling of each cell's outgoing fluxes
    Field2D u_lo_, u_hi_;    // u -/+ 2a_x per cell at the start of the update
    Field2D v_lo_, v_hi_;    // v -/+ 2a_y
    Field2D speed_hi_;       // along-surface speed + 2 sqrt(k g_n h_n)
    double k_max_;           // largest earth-pressure coefficient
    // Small active areas run on one thread: a parallel region costs tens of
    // microseconds to wake the team, more than the work of a few thousand cells, and
    // on a shared machine a descheduled thread stalls every region (a 0.5 s test took
    // 10 s on two threads). Results do not depend on it.
    static constexpr std::size_t kMinCellsPerThreadedStep = 20000;
    bool threaded_ = false;
    double outflow_volume_ = 0.0;
    std::uint64_t cell_updates_ = 0;
};

}  // namespace avalanche
