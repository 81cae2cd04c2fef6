// SPDX-License-Identifier: MIT
// Deterministic, seeded ray/box query generators shared by the model tests,
// the fixed-point tests, the cocotb benches and the RTL stress runs.
//
// The same seed gives the same queries on every platform (own PRNG, no
// std:: distributions). Every query is valid (validate_query accepts it),
// and every origin and box plane lies in [-1, 1], so the fixed-point format
// (range [-2, 2)) can take them all.
#pragma once

#include "pluecker/geometry.hpp"

#include <cstddef>
#include <cstdint>
#include <vector>

namespace pluecker {

// Origins and boxes uniform in [-1,1]^3; half of the rays aimed at a point
// in or near the box (so hits and near misses are common), the others in a
// uniformly random direction; a quarter of all queries are finite segments.
std::vector<Query> random_queries(std::uint64_t seed, std::size_t n);

// Queries at the edges of what a float or fixed-point test resolves. Query
// k belongs to family k % extreme_family_count(); the families are listed
// in querygen.cpp (axis-parallel, near-axis, signed zeros, exact edge and
// corner hits and their 1-ulp neighbours, flat/line/point boxes, origins on
// the box, segments ending on a face, +-1 coordinates, denormal, tiny and
// huge directions, tiny boxes, zero-length segments).
// When `families` is given it receives the family index of every query.
std::vector<Query> extreme_queries(std::uint64_t seed, std::size_t n,
                                   std::vector<std::size_t>* families = nullptr);

std::size_t extreme_family_count();
// Short name of family i ("axis-parallel", ...); "?" when i is out of range.
const char* extreme_family_name(std::size_t i);

}  // namespace pluecker
