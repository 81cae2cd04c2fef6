// SPDX-License-Identifier: MIT
// Deterministic, seeded ray/box query generators shared by the model tests,
// the fixed-point tests, the cocotb benches and the RTL stress runs.
//
// The same seed gives the same queries on every platform (own PRNG, no
// std:: distributions). Every query is valid (validate_query accepts it).
// random_queries and extreme_queries keep every origin and box plane in
// [-1, 1]; setup_queries sends rays from anywhere into boxes of one
// fixed-point range. port_range_queries and boundary_queries make operands
// of the datapath itself (FixedRay, FixedBox), which no float query set-up
// produces.
#pragma once

#include "pluecker/fixed.hpp"
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

// The rays a renderer traces, from anywhere, into boxes of the fixed-point
// range of COORD_BITS = coord_bits (every box inside [-2, 2 - 2^(2-C)]^3;
// origins anywhere finite): the families of fixed.hpp's ray set-up.
// Query k belongs to family k % setup_family_count():
//   far-corner, far-edge  cameras and lights up to 1e6 away through a box
//                         corner or edge exactly, then one ulp off on a
//                         direction component or a box plane;
//   far-aimed             far cameras aimed in float at edges and corners;
//   light-ray             shadow rays to far lights, and rays from the
//                         light ending exactly on the entry face it sees;
//   long-dir              |d| up to ~100, segments ending exactly on the
//                         entry face or one ulp before or after it;
//   range-edge            origins on the range cube's faces or one ulp
//                         outside, rays along a face, rays through the
//                         cube's edges, boxes touching the range limits.
// InputError when coord_bits is outside 6..24.
std::vector<Query> setup_queries(std::uint64_t seed, std::size_t n, int coord_bits,
                                 std::vector<std::size_t>* families = nullptr);
std::size_t setup_family_count();
const char* setup_family_name(std::size_t i);

// One query as the datapath's ports take it.
struct FixedQuery {
    FixedRay ray;
    FixedBox box;
};

// Operands drawn straight from the port ranges of f: any C-bit
// coordinates (corner values -2^(C-1), -2^(C-1)+1, -1, 0, 1, 2^(C-1)-2,
// 2^(C-1)-1 often), any D-bit direction up to 2^D - 1 (beyond the set-up's
// 2^(D-1)), boxes with LO > HI on some axes, any class, segment ends or
// none. Checks that no intermediate of the RTL overflows. InputError for a
// bad format.
std::vector<FixedQuery> port_range_queries(std::uint64_t seed, std::size_t n, const FixedFormat& f);

// Operands placed exactly on a decision boundary of one test of the
// datapath (fixed.hpp), every other test passing with room, so that an
// off-by-one anywhere (a margin term, >= against >, an end rounding) flips
// the answer. Query k is of kind k % boundary_kind_count():
//   edge (three in five)  one edge test at 2*T_ij + M_ij in {-2, -1, 0, 1}
//                         (conservative: on the margin's bound) or T_ij in
//                         {-1, 0, 1} (nearest)
//   end                   one G_i in {-1, 0, 1}
//   origin                one B_i in {-1, 0, 1}
// Only operands are chosen here; the answer is fixed_hit's. When `kinds`
// is given it receives the kind of every query (boundary_kind_name).
// InputError for a bad format.
std::vector<FixedQuery> boundary_queries(std::uint64_t seed, std::size_t n, const FixedFormat& f,
                                         std::vector<std::size_t>* kinds = nullptr);
std::size_t boundary_kind_count();
const char* boundary_kind_name(std::size_t i);

}  // namespace pluecker
