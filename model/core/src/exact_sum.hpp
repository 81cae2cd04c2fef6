// SPDX-License-Identifier: MIT
// Exact signs and roundings of short sums of exact float products: the
// arithmetic under the exact test (exact.cpp) and the exact ray clip of the
// fixed-point set-up (fixed.cpp).
#pragma once

#include <cstdint>

namespace pluecker::detail {

// The exact sign (-1, 0 or 1) of p[0] + ... + p[n-1], 1 <= n <= 4. Every
// p[k] must be a multiple of 2^-298 below 2^600 in magnitude: an exact
// product of two floats, or such a product times a power of two (2^-298 is
// the smallest nonzero float*float, 2^-149 squared).
int exact_sign_of_sum(const double* p, int n);

// The integer nearest to (p[0] + ... + p[n-1]) / q, ties to even, exactly;
// 1 <= n <= 3, every p[k] as for exact_sign_of_sum, q a positive float.
// The quotient must be below 2^limit_bits in magnitude (the callers'
// quotients are fixed-point coordinates: 2^24 for the global datapath's
// widths, up to 2^62 for the local frames' grid); std::logic_error
// otherwise.
std::int64_t exact_round_ratio(const double* p, int n, float q, int limit_bits = 24);

}  // namespace pluecker::detail
