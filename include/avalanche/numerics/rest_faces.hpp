#pragma once
// Faces that Coulomb friction holds at rest (numerics.rest_faces; MODEL.md 2.4,
// docs/numerics.md "Piles at rest").
//
// The paper's scheme is not well-balanced for Coulomb friction: between two cells at
// rest with different depths the HLLC mass flux is about -a/2 (h_R - h_L), a numerical
// diffusion of the depth that friction, applied to the momentum afterwards, cannot
// undo, so a pile that should stand creeps. In the spirit of the well-balanced
// treatments of Bouchut et al. (2003) and Fernandez-Nieto et al. (2008), friction enters
// the flux as a threshold: a face between two cells that the last friction stage held
// at rest (or between such a cell and a dry one), across which the static driving
// acceleration of the material (gravity along the bed and the face's pressure
// gradient) is below the Coulomb limit tan(delta) g_n, passes no mass and no
// tangential momentum, and its normal momentum flux is the two cells' mean hydrostatic
// pressure: the material on either side feels the pressure, which friction then holds,
// and no mass moves. Where the limit is exceeded, or either cell moves, the face keeps
// the scheme's flux.
#include <cstddef>
#include <cstdint>

namespace avalanche {

// Per cell: 1 where the last friction stage held the cell at rest (its velocity after
// the sources is exactly zero), 0 elsewhere. The state's layout, ghost cells included.
using HeldFlag = std::uint8_t;

// One row of faces, face f between the cells "l" and "r" read at index f of the
// pointers below (x-faces: l = cell f - 1 of the row, r = cell f; y-faces: l = cell f of
// the row below, r = cell f of the row). n: the face's normal direction, t: the other.
struct RestFaceRowInput {
    const double *h_l, *h_r;          // depth (the state's thickness)
    const HeldFlag *held_l, *held_r;  // held at rest by friction (see above)
    const double *c_l, *c_r;          // pressure coefficients k p of the normal direction
    const double *an_l, *an_r;        // non-friction source acceleration, normal component
    const double *at_l, *at_r;        // ... tangential component
    const double *gn_l, *gn_r;        // bed-normal gravity (the friction load at rest)
    const double *sn_l, *sn_r;        // surface gradient, normal (null in bed-fitted frames)
    const double *st_l, *st_r;        // ... tangential
    // In the DEM frame (sn, st set) an, at and gn are not read (null: the terrain does not
    // store them): they are computed from the slopes with this g (TerrainFields::
    // slope_gravity, dem_coefficients.hpp); x_faces says which slope is z_x (sn on
    // x-faces, st on y-faces), so that the values are the terrain's to the bit.
    double slope_gravity = 0.0;
    bool x_faces = true;
};

struct RestFaceRowParams {
    double inv_dn;     // 1 / cell size across the face
    double tan_delta;  // tan of the bed friction angle
    double h_min;      // thinner cells count as dry
};

// Replaces the fluxes (mass fh, normal momentum fn, tangential momentum ft) of faces
// f0 .. f1 - 1 that friction holds (see above). Returns how many it replaced.
int hold_rest_faces_row(const RestFaceRowInput& in, const RestFaceRowParams& p, double* fh,
                        double* fn, double* ft, int f0, int f1) noexcept;

// After the advection's update of one row: a cell held at rest (held[i]) whose four
// faces passed no mass (the mass fluxes fx_h of faces i and i + 1, fy_h of faces i and
// i + stride; a held cell's faces are held, or face dry cells) keeps its zero momentum:
// the pressure its faces carry and gravity are held by the bed's friction, whose limit
// the faces' test checked. Without this, the pressure of a deep cell on a thin one
// beside it (the mean of the two, which a single face flux carries to both) would set
// the thin one moving. Writes held_next[i] (if not null): held and quiet, the flags of
// the next advection when no friction stage comes between. Cells i0 .. i1 - 1.
void keep_held_at_rest(const HeldFlag* held, const double* fx_h, const double* fy_h,
                       std::ptrdiff_t stride, double* hu, double* hv, HeldFlag* held_next, int i0,
                       int i1) noexcept;

// held[i] = 1 where a wet cell (h >= h_min) has zero momentum, else 0, for i0 .. i1 - 1:
// the friction stage's result for the cells it stopped (a stopped cell's momentum is
// set to exactly zero, cell_rows.hpp).
void held_at_rest_row(const double* h, const double* hu, const double* hv, double h_min,
                      HeldFlag* held, int i0, int i1) noexcept;

}  // namespace avalanche
