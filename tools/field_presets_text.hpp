#pragma once
// The fixed prose of the field-presets section of docs/performance.md
// (field_presets_study.cpp writes the numbers between them).
namespace field_presets_text {

inline constexpr const char* kIntro = R"(
The chute above has a deposit about as deep as the fine preset's cells there (0.27 m on
0.25 m). A rock avalanche leaves tens of metres of debris on cells of 10-20 m, so with
the fine preset its cells are a quarter to a half of the deposit's depth. This study runs
the field scene (`scenarios/field_fluchthorn`: 7 x 10^6 m³ released, delta 20°, 20 m
cells, 180 s) with each preset and, on the fine preset's 10 m cells, at other Courant
numbers and with the standard numerics, and compares the maps with a run on 5 m cells
(4x finer than the scenario, as the chute's reference) with the standard numerics.
Errors are relative L1 distances from the reference's map averaged onto each run's
cells (cells never reached count as 0): the deposit (`deposit_thickness.tif`), the
maximum depth and the maximum speed (the hazard classes come from the maxima). The last
column is the root-mean-square speed, at the end, of the cells deeper than 1 m: how
still the deposit is. Every run is the command a user types, on one thread; CPU time of
the whole command (preparation, run and products), or its summary's wall time in
parentheses when the run was reused from an earlier regeneration.
)";

inline constexpr const char* kDiscussion = R"(
Every run ends at the scenario's end time: on this scene thin layers keep sliding on
slopes steeper than delta (final kinetic energy 1-4 x 10^-3 of its maximum), which says
nothing about the deposit. The last column does. With one advection per step at Courant
0.4 on cells a quarter to half of the deposit's depth, the Savage-Hutter regimes of
neighbouring deep cells flip with the noise, and their pressures (k_pass / k_act apart)
push them against each other faster than friction stops them (docs/numerics.md,
advection step 2): the push of one advection scales with its Courant number, so the
deposit calms as the Courant number falls. Until 2026-12-02 the fine preset was S L S at
Courant 0.4, chosen on the chute, where it is the cheapest and the most accurate choice
at 0.25 m; on this scene its deposit map was farther from the reference than that of the
standard numerics on the same cells. The fine preset is now S L S at Courant 0.2 (one
advection per step at the advection Courant number of L S L at 0.4): on the chute it costs
about twice Courant 0.4 for 1.3x its deposit error, still below the standard numerics on
the same cells in both error and cost; here its deposit is the closest of all runs to the
reference (its maximum speed a little farther than Courant 0.4's), at about half the cost
of the standard numerics on the same cells. The check a
map is defended with must not depend on how deep its deposit is against its cells
(tests/regression/test_field_deposit.cpp runs the fine preset on this scene and bounds
the deep cells' speed). The draft preset keeps Courant 0.4: its cells are twice the
scenario's, as deep as the deposit or deeper. The maps of maxima move less than the
deposit between these runs on 10 m cells; from 20 m to 10 m cells (standard to fine)
every map's error falls by about half or more: the cell size still matters most.
)";

}  // namespace field_presets_text
