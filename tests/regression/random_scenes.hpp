#pragma once
// Random scenes for the extreme-case matrix's random sweep (test_random_extremes.cpp).
// The matrix (extreme_scenes.hpp) moves one parameter at a time from a baseline on
// idealised terrain; these scenes draw every parameter at once over the same ranges,
// on rough DEMs with cliffs, pits and walls, several releases, some of them moving, so
// that corners the one-at-a-time sweeps do not reach meet: a 200 m release with
// h_min 1e-8 at Courant 0.5 on a 100 m step, a frictionless film on a wall boundary.
// A seed names a scene: the same seed gives the same scene on every platform (the
// draws use only mt19937_64's integers, whose sequence the standard fixes).
#include <cstdint>
#include <string>

#include "avalanche/numerics/active_box.hpp"
#include "extreme_scenes.hpp"

namespace avalanche::extremes {

struct RandomScene {
    Scene scene;
    std::string description;  // every drawn parameter, to rebuild the case by hand
};

RandomScene random_scene(std::uint64_t seed);

// The scene mirrored across the grid's vertical centre line (Axis::x: i -> nx-1-i, u
// reversed) or its horizontal one (Axis::y: j -> ny-1-j, v reversed): terrain, release
// and velocities. Its terrain is made at once, the scene's on demand (the same values).
enum class Axis { x, y };
Scene mirrored(const Scene& s, Axis axis);

// The scene on the cells of `box` only: a grid of the box's size at the box's place,
// the elevations, the release and the velocities of those cells. Its terrain is made at
// once.
Scene cropped(const Scene& s, const ActiveBox& box);

// Whether a state of `s` and a state of mirrored(s, axis) are mirror images: every
// value equal (-0 equal to +0), the reversed momentum with its sign changed.
bool mirror_images(const State& a, const State& b, Axis axis);

}  // namespace avalanche::extremes
