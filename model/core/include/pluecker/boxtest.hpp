// SPDX-License-Identifier: MIT
// Float ray/box tests in the report's eight-class form, and the exact test.
//
// Every test answers: does the segment {o + t*d : 0 <= t <= tmax} meet the
// closed box? (tmax = inf: the unbounded ray.) A ray is set up once
// (class, inverse direction, ...) and then tested against many boxes, as a
// traversal does.
#pragma once

#include "pluecker/geometry.hpp"

namespace pluecker {

// 'smits-mul-cls': slab test with the inverse direction, planes selected by
// the ray class, multiplications only.
struct SmitsRay {
    Vec3 o;
    Vec3 inv;  // 1/d per component (+-inf for +-0)
    float tmax;
    RayClass cls;
};
SmitsRay smits_setup(const Ray& r);
// On a hit, *tnear (if given) receives the entry distance max(0, t_enter).
bool smits_hit(const SmitsRay& r, const Box& b, float* tnear = nullptr);

// 'pluecker-cls': Mahovsky's division-free test: origin test, six 2x2
// determinant sign tests on the silhouette edges, and the segment endpoint
// test when tmax is finite.
struct PlueckerRay {
    Vec3 o;
    Vec3 d;
    Vec3 e;  // segment end o + tmax*d (valid when has_end)
    bool has_end;
    RayClass cls;
};
PlueckerRay pluecker_setup(const Ray& r);
bool pluecker_hit(const PlueckerRay& r, const Box& b);

// Ground truth: exact rational arithmetic on the same float inputs.
// Requires a valid query (see validate_query); d may have zero components
// but not all three.
bool exact_hit(const Ray& r, const Box& b);

}  // namespace pluecker
