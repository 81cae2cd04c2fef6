// SPDX-License-Identifier: MIT
// The ground truth: the ray/box answer in exact arithmetic on the float
// inputs. Every accuracy figure of the project is measured against it.
//
// Definition. Per axis i with D_i = |d_i| > 0 the ray is inside the closed
// slab for t in [A_i / D_i, B_i / D_i], with the signed plane offsets along
// the ray
//     A_i = n_i ? o_i - hi_i : lo_i - o_i   (entry)
//     B_i = n_i ? o_i - lo_i : hi_i - o_i   (exit)
// (n_i = the sign bit of d_i). An axis with d_i = +-0 never changes, so it
// admits every t when lo_i <= o_i <= hi_i and none otherwise. The segment
// meets the box iff the intersection of [0, tmax] with the slab intervals is
// not empty, i.e. iff
//     max(0, A_i/D_i over moving axes) <= min(tmax, B_j/D_j over moving axes)
// (tmax = inf drops the tmax bound). Max <= min holds iff every entry bound
// is <= every exit bound, so the code compares all entry/exit pairs, each
// as an exact comparison of two fractions with positive denominators:
//     p/q <= r/s  <=>  p*s <= r*q.
//
// Exactness. Each fraction has the form (x - y) / q with x, y, q floats, so
// p*s - r*q expands into four products of two floats. A product of two
// floats has at most 24+24 = 48 significant bits and a binary exponent in
// [-298, 256], so it is exact in a double. The comparison is thus the sign
// of a sum of four exact doubles, found by
//   1. a filter: the sum s computed in double, with the rounding error of
//      three additions bounded by 3u * sum|p_k| (u = 2^-53, Higham's gamma_3
//      with slack; multiplications are exact, additions cannot underflow
//      inexactly); when |s| exceeds 8u * sum|p_k|, sign(s) is the exact sign;
//   2. otherwise exact integers: every product is a multiple of 2^-298, so
//      p_k * 2^298 is an integer below 2^554, converted exactly by
//      mpz_set_d, and summed in GMP.
#include "pluecker/boxtest.hpp"

#include "exact_sum.hpp"

#include <gmp.h>

#include <cmath>
#include <stdexcept>

namespace pluecker {

namespace detail {

namespace {

constexpr int kProductScale = 298;  // p * 2^298 is an integer for p = float*float

// Scratch integers of the slow paths, one set per thread.
struct Scratch {
    mpz_t sum, term, den, rem;
    Scratch() {
        mpz_init2(sum, 640);
        mpz_init2(term, 640);
        mpz_init2(den, 640);
        mpz_init2(rem, 640);
    }
    ~Scratch() {
        mpz_clear(sum);
        mpz_clear(term);
        mpz_clear(den);
        mpz_clear(rem);
    }
    Scratch(const Scratch&) = delete;
    Scratch& operator=(const Scratch&) = delete;
};
thread_local Scratch z;

// z.sum = (p[0] + ... + p[n-1]) * 2^298, exactly.
void exact_scaled_sum(const double* p, int n) {
    mpz_set_ui(z.sum, 0);
    for (int k = 0; k < n; ++k) {
        mpz_set_d(z.term, std::ldexp(p[k], kProductScale));  // an integer: exact
        mpz_add(z.sum, z.sum, z.term);
    }
}

}  // namespace

int exact_sign_of_sum(const double* p, int n) {
    double s = 0.0, mag = 0.0;
    for (int k = 0; k < n; ++k) {
        s += p[k];
        mag += std::fabs(p[k]);
    }
    if (mag == 0.0) return 0;  // every term is zero
    const double bound = 0x1p-50 * mag;  // 8u * sum|p|, u = 2^-53
    if (s > bound) return 1;
    if (s < -bound) return -1;
    exact_scaled_sum(p, n);  // slow path: exact integer sum
    return mpz_sgn(z.sum);
}

std::int64_t exact_round_ratio(const double* p, int n, float q, int limit_bits) {
    if (n < 1 || n > 3 || !(q > 0.0f) || limit_bits < 1 || limit_bits > 62)
        throw std::logic_error("exact_round_ratio: bad arguments");
    const double limit = std::ldexp(1.0, limit_bits);
    // Fast path: a candidate k from the double quotient, confirmed by exact
    // signs of sum - (k -+ 1/2) * q. For |k| < 2^28, (k -+ 1/2) * q has at
    // most 29 + 24 significant bits, so it is exact in a double and a
    // multiple of 2^-150; larger quotients take the slow path.
    constexpr double kFastLimit = 0x1p28;
    double s = 0.0;
    for (int i = 0; i < n; ++i) s += p[i];
    double k = std::nearbyint(s / static_cast<double>(q));
    for (int step = 0; step < 3 && std::fabs(k) < kFastLimit && std::fabs(k) < limit; ++step) {
        double t[4] = {p[0], n > 1 ? p[1] : 0.0, n > 2 ? p[2] : 0.0, -(k - 0.5) * static_cast<double>(q)};
        const int below = exact_sign_of_sum(t, 4);  // sign of v - (k - 1/2)
        if (below < 0) {
            k -= 1;
            continue;
        }
        t[3] = -(k + 0.5) * static_cast<double>(q);
        const int above = exact_sign_of_sum(t, 4);  // sign of v - (k + 1/2)
        if (above > 0) {
            k += 1;
            continue;
        }
        const bool odd = std::fmod(k, 2.0) != 0.0;
        if (below == 0 && odd) k -= 1;  // v = k - 1/2: to even
        if (above == 0 && odd) k += 1;  // v = k + 1/2: to even
        return static_cast<std::int64_t>(k);
    }
    // Slow path (heavy cancellation): floor division of exact integers.
    exact_scaled_sum(p, n);
    mpz_set_d(z.den, std::ldexp(static_cast<double>(q), kProductScale));
    mpz_fdiv_qr(z.term, z.rem, z.sum, z.den);  // sum = term * den + rem, 0 <= rem < den
    mpz_mul_2exp(z.rem, z.rem, 1);
    const int c = mpz_cmp(z.rem, z.den);  // 2 rem against den
    if (c > 0 || (c == 0 && mpz_odd_p(z.term))) mpz_add_ui(z.term, z.term, 1);
    if (!mpz_fits_slong_p(z.term) || std::fabs(static_cast<double>(mpz_get_si(z.term))) >= limit)
        throw std::logic_error("exact_round_ratio: quotient out of range");
    return mpz_get_si(z.term);
}

}  // namespace detail

namespace {

using detail::exact_sign_of_sum;

// A bound of a slab interval: (x - y) / q with q > 0.
struct Frac {
    float x, y, q;
};

// Exact a.x-a.y over a.q <= b.x-b.y over b.q, i.e. (b.x - b.y)*a.q - (a.x - a.y)*b.q >= 0.
bool frac_le(const Frac& a, const Frac& b) {
    const double p[4] = {
        double(b.x) * double(a.q),
        -(double(b.y) * double(a.q)),
        -(double(a.x) * double(b.q)),
        double(a.y) * double(b.q),
    };
    return exact_sign_of_sum(p, 4) >= 0;
}

}  // namespace

bool exact_hit(const Ray& r, const Box& b) {
    Frac entry[4];
    Frac exit[4];
    int n_entry = 0, n_exit = 0;
    entry[n_entry++] = {0.0f, 0.0f, 1.0f};                              // t >= 0
    if (!std::isinf(r.tmax)) exit[n_exit++] = {r.tmax, 0.0f, 1.0f};  // t <= tmax
    for (int a = 0; a < 3; ++a) {
        const float d = r.d[a];
        if (d == 0.0f) {  // +0 or -0: the coordinate stays o_a for every t
            if (!(b.lo[a] <= r.o[a] && r.o[a] <= b.hi[a])) return false;
            continue;
        }
        const float q = std::fabs(d);
        if (std::signbit(d)) {
            entry[n_entry++] = {r.o[a], b.hi[a], q};
            exit[n_exit++] = {r.o[a], b.lo[a], q};
        } else {
            entry[n_entry++] = {b.lo[a], r.o[a], q};
            exit[n_exit++] = {b.hi[a], r.o[a], q};
        }
    }
    for (int i = 0; i < n_entry; ++i)
        for (int j = 0; j < n_exit; ++j)
            if (!frac_le(entry[i], exit[j])) return false;
    return true;
}

}  // namespace pluecker
