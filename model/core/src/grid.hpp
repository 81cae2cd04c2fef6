// SPDX-License-Identifier: MIT
// Exact rounding onto a fixed-point grid: the ray set-up steps shared by the
// global datapath (fixed.cpp) and the local frames (local.cpp).
//
// A grid of B bits holds the integers [-2^(B-1), 2^(B-1) - 1]; integer q is
// the value q * 2^-(B-2), so the grid spans [-2, 2 - 2^-(B-2)]. The *float
// range* of a grid is the cube of floats a box plane may take:
// [-2, 2 - 2^-min(B-2, 23)] per axis (above B = 25 the grid's upper end is
// not a float; the largest float below 2 is 2 - 2^-23). Every step below is
// exact: its result is the mathematically exact value rounded once, as
// stated.
#pragma once

#include "pluecker/geometry.hpp"

#include <array>
#include <cmath>
#include <cstdint>
#include <string>

namespace pluecker::detail {

using i64 = std::int64_t;

// Round an exact value s + err (s a double, err the exact rounding error of
// a TwoSum, |err| <= ulp(s)/2, |s| < 2^52) to an integer.
inline double floor_exact(double s, double err) {
    double f = std::floor(s);
    if (s == f && err < 0) f -= 1;
    return f;
}
inline double ceil_exact(double s, double err) {
    double c = std::ceil(s);
    if (s == c && err > 0) c += 1;
    return c;
}
inline double nearest_exact(double s, double err) {
    const double f = floor_exact(s, err);
    // s - f and (s - f) - 0.5 are exact: both are small multiples of ulp(s).
    const double h = (s - f) - 0.5;
    if (h > -err) return f + 1;
    if (h < -err) return f;
    return std::fmod(f, 2.0) == 0 ? f : f + 1;  // tie: to even
}

// Exact s + err = a + b (Knuth's TwoSum).
inline void two_sum(double a, double b, double& s, double& err) {
    s = a + b;
    const double bb = s - a;
    err = (a - (s - bb)) + (b - bb);
}

// "x", "y" or "z"; a float as error messages print it (9 digits).
const char* axis_name(int a);
std::string fmt_float(float v);

enum class Round { Down, Up, Nearest };

// The grid's integer range.
inline i64 grid_min(int bits) { return -(i64{1} << (bits - 1)); }
inline i64 grid_max(int bits) { return (i64{1} << (bits - 1)) - 1; }
inline bool in_grid(double q, int bits) {
    return q >= static_cast<double>(grid_min(bits)) && q <= static_cast<double>(grid_max(bits));
}
// The float range (above) as a box.
Box grid_float_range(int bits);

// Coordinate x (a float, so x * 2^(B-2) is exact in a double) on the grid,
// rounded by `mode` (not range-checked).
double round_to_grid(float x, Round mode, int bits);

// round(|x| / m * 2^(bits - 1)) to nearest, ties to even, exactly; |x| <= m,
// m > 0, any bits (the result is 0 when it rounds below 1/2). The result
// must be below 2^62.
i64 scaled_direction(float x, float m, int bits);

// Throws InputError for a non-finite origin, a zero, NaN or infinite
// direction, or a negative or NaN tmax.
void check_ray(const Ray& r);

bool inside(const Vec3& p, const Box& b);

// The origin of a ray that starts outside the float range of the grid but
// meets it (exact_hit): the point p = o + t0*d where the segment enters the
// range (t0 the exact entry parameter, chosen by exact comparisons), every
// coordinate the exact rational value rounded to nearest on the grid.
std::array<i64, 3> clipped_origin(const Ray& r, int bits);

// The segment end e = o + tmax*d of the ray as given, exactly, on the grid:
// rounded outward along the ray (ceil on positive axes of class `cls`,
// floor on negative ones) or to nearest. Returns false (no end) when tmax
// is infinite or a coordinate leaves the grid: the ray is then treated as
// unbounded, which can only add hits. Throws InputError for a negative or
// NaN tmax.
bool segment_end(const Ray& r, RayClass cls, bool outward, int bits, std::array<i64, 3>& end);

}  // namespace pluecker::detail
