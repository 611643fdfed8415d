#pragma once
// Equality to the bit, what the tests that compare two runs, kernels or files assert:
// NaN equals a NaN of the same bits, and -0 differs from +0, unlike operator==.
#include <cstring>
#include <span>

#include "avalanche/core/field.hpp"
#include "avalanche/core/state.hpp"

namespace avalanche::test {

inline bool same_bits(double a, double b) { return std::memcmp(&a, &b, sizeof a) == 0; }

// Two arrays of no elements are the same; memcmp must not be given their data, which
// may be null (an optional field not made, an empty dataset).
inline bool same_bits(std::span<const double> a, std::span<const double> b) {
    return a.size() == b.size() && (a.empty() || std::memcmp(a.data(), b.data(), a.size_bytes()) == 0);
}

// The fields' stored values: a field of one row for all (Field2D::same_in_every_row)
// differs from a full one of the same values. Every cell, ghosts included (not the
// rows' padding, which no cell is).
inline bool same_bits(const Field2D& a, const Field2D& b) {
    return a.same_in_every_row() == b.same_in_every_row() && same_bits(a.packed(), b.packed());
}

// Two states: depth and both momenta, ghost cells included.
inline bool same_bits(const State& a, const State& b) {
    return same_bits(a.h, b.h) && same_bits(a.hu, b.hu) && same_bits(a.hv, b.hv);
}

}  // namespace avalanche::test
