#pragma once
// One time step of the Savage–Hutter solver: Strang splitting of advection L and
// point-wise sources S (Wang & Li 2017 eq. 12), with
//  - L: unsplit WAF-TVD fluxes on states advanced half a step by a transverse
//    first-order Godunov predictor (eqs. 6-9), or the first-order HLLC Godunov flux;
//  - the thin-layer wet/dry rule (section 2.2.3): cells thinner than h_min do not
//    export mass, take the velocity of their deepest wet neighbour, or stop;
//  - a conservative positivity limiter that scales the outgoing face fluxes of a
//    cell that would otherwise be emptied below zero;
//  - S: tangential gravity, then Coulomb friction as a stopping magnitude;
//  - an energy cap: no cell is faster than a frictionless point mass falling from
//    the highest free surface of the state the run started from, plus that state's
//    kinetic and pressure energy (docs/numerics.md, "Energy cap").
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
    // Energy budget per unit mass (m^2/s^2) behind the speed cap: fixed by the first
    // step() from the state it starts from, +infinity (no cap) until then. A restart
    // from a checkpoint must restore it to reproduce the uninterrupted run bitwise.
    [[nodiscard]] double energy_budget() const { return energy_budget_; }
    void set_energy_budget(double b) {
        energy_budget_ = b;
        budget_set_ = true;
    }
    // The budget of a state: max over wet cells of
    //   |u|^2/2 + g (z_b + h_n g/g_n) + 2 k_max g_n h_n.
    [[nodiscard]] double energy_budget_of(const State& s) const;
    // Number of cell updates performed (active cells x steps).
    [[nodiscard]] std::uint64_t cell_updates() const { return cell_updates_; }

    // The operators, public for tests of the splitting.
    void advect(State& s, double tau);
    void apply_sources(State& s, double dt) const;
    void fill_ghosts(State& s) const;  // every ghost cell

private:
    void fill_ghosts_near(State& s, const ActiveBox& near) const;
    void update_pressure_coefficients(const State& s);
    void godunov_predictor(const State& s, double tau, bool along_x);
    void face_fluxes(const State& s, const State& predicted, double tau, bool along_x, bool waf);
    void fix_boundary_faces(const State& s);
    void limit_and_update(State& s, double tau);
    void thin_layer_velocities(State& s) const;
    void shrink_box_to_wet(const State& s, const ActiveBox& search);
    [[nodiscard]] double energy_budget_in(const State& s, const ActiveBox& wet) const;
    // Square of the largest true speed the energy budget allows at bed elevation z
    // (negative: the cell lies above what the material can reach).
    [[nodiscard]] double speed_cap2(double z) const { return 2.0 * (energy_budget_ - numerics_.gravity * z); }

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
    State pred_;             // state advanced by the transverse predictor of the current sweep;
                             // its h holds the donor factors during the update
    State flux_x_, flux_y_;  // face fluxes; flux_x_(i, j) is the face left of cell i
    Field2D u_lo_, u_hi_;    // u -/+ 2a_x per cell at the start of the update
    Field2D v_lo_, v_hi_;    // v -/+ 2a_y
    Field2D speed_hi_;       // along-surface speed + 2 sqrt(k g_n h_n)
    double k_max_;           // largest earth-pressure coefficient
    double energy_budget_;   // see energy_budget(); +infinity = not set
    bool budget_set_ = false;
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
