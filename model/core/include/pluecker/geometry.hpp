// SPDX-License-Identifier: MIT
// Rays, boxes and ray classes shared by every part of the model.
#pragma once

#include <glm/common.hpp>
#include <glm/vec3.hpp>

#include <cmath>
#include <cstdint>
#include <limits>
#include <stdexcept>
#include <string>

namespace pluecker {

using Vec3 = glm::vec3;

inline constexpr float kInf = std::numeric_limits<float>::infinity();

// A ray o + t*d for 0 <= t <= tmax; tmax = +inf means an unbounded ray.
struct Ray {
    Vec3 o{0.0f};
    Vec3 d{0.0f, 0.0f, 1.0f};
    float tmax = kInf;
};

// A closed axis-aligned box [lo, hi].
struct Box {
    Vec3 lo{kInf};
    Vec3 hi{-kInf};

    void grow(const Vec3& p) {
        lo = glm::min(lo, p);
        hi = glm::max(hi, p);
    }
    void grow(const Box& b) {
        lo = glm::min(lo, b.lo);
        hi = glm::max(hi, b.hi);
    }
    bool empty() const { return lo.x > hi.x || lo.y > hi.y || lo.z > hi.z; }
    Vec3 center() const { return 0.5f * (lo + hi); }
    Vec3 extent() const { return hi - lo; }
    float half_area() const {
        const Vec3 e = extent();
        return e.x * e.y + e.y * e.z + e.z * e.x;
    }
};

// One ray/box query: the unit of work of every box test and of the RTL.
struct Query {
    Ray ray;
    Box box;
};

// Ray class (Mahovsky & Wyvill, JGT 9(1), 2004): one bit per axis, set when
// the direction component is negative (sign bit, so -0 counts as negative).
// Bit 0 is x, bit 1 is y, bit 2 is z. The report names the classes MMM..PPP
// with x first; class_name() prints that name.
using RayClass = std::uint8_t;

inline RayClass ray_class(const Vec3& d) {
    return static_cast<RayClass>((std::signbit(d.x) ? 1u : 0u) | (std::signbit(d.y) ? 2u : 0u) |
                                 (std::signbit(d.z) ? 4u : 0u));
}
inline bool class_negative(RayClass c, int axis) { return (c >> axis) & 1u; }

inline std::string class_name(RayClass c) {
    std::string s;
    for (int a = 0; a < 3; ++a) s += class_negative(c, a) ? 'M' : 'P';
    return s;
}

// Raised for every kind of bad input: a mesh, a query line, a flag or a
// binding argument. what() names the thing and where it is.
struct InputError : std::runtime_error {
    using std::runtime_error::runtime_error;
};

}  // namespace pluecker
