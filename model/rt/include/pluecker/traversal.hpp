// SPDX-License-Identifier: MIT
// BVH traversal: closest hit and any hit over the box tests of boxtest.hpp
// and fixed.hpp, with the child orders of Mahovsky's 2005 report. This
// header: the choices (box test, child order), the counters, the stack, and
// the runtime interface (Tracer, make_tracer). The rest of the traversal:
// accel.hpp (the memory layout), box_kernels.hpp, policies.hpp,
// traverse_loops.hpp, batched.hpp (hardware in the loop); traverse.hpp
// gathers them.
//
// Traversal (all paths)
//   The root box is tested first. At an interior node both child boxes are
//   tested (two box tests); when both are hit the first child (by the child
//   order) is visited next and the other is pushed on a stack; a leaf tests
//   its triangles with the watertight test (triangle.hpp). Closest hit
//   shrinks the ray's tmax, as the box tests see it, to the current best hit;
//   any hit stops at the first triangle hit in [0, tmax].
//   Counted: node visits (every node entered, leaves included), box tests
//   (every box test call, the root's included), triangle tests.
//
// Child orders
//   fixed  child 0 first.
//   dsa    the report's direction/split-axis order: child 0 holds the lower
//          side of the split axis, so a ray negative along the split axis
//          visits child 1 first, a positive one child 0. Kept as an explicit
//          table over the 8 ray classes and 3 axes (kDsaFirstChild).
//   dist   nearer entry distance first (needs the distance the slab test
//          yields: smits only); a popped node farther than the current best
//          hit is skipped.
//
// The report's configurations: smits-mul-cls (smits + fixed), smits-dist,
// smits-dsa, pluecker-cls (pluecker + fixed), pluecker-dsa; besides them the
// exact test and the fixed-point test (fixed or dsa order).
//
// Fixed-point path
//   Every ray is set up once by fixed_setup_ray (fixed.hpp): a ray from
//   outside the range cube is clipped exactly onto it, a ray that misses
//   the cube hits nothing. Shrinking tmax to a hit at t recomputes only the
//   segment end, from the ray as given (fixed_setup_end). Box queries are
//   recorded with the ray as given and its current tmax.
#pragma once

#include "pluecker/geometry.hpp"
#include "pluecker/mesh.hpp"
#include "pluecker/query.hpp"
#include "pluecker/triangle.hpp"

#include <array>
#include <cstddef>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

namespace pluecker {

// ---------------------------------------------------------------------------
// The choices of a traversal, and their names in output (the applications
// parse them: pluecker/app/names.hpp)

// F32Pluecker, F32PlueckerCons, F32Smits: the binary32 units' bit-exact
// models (f32unit.hpp: the Plücker unit rounding to nearest, the same unit
// rounding outward, the slab unit).
enum class BoxTestKind { Exact, Smits, Pluecker, Fixed, Local, F32Pluecker, F32PlueckerCons, F32Smits };
enum class ChildOrder { Fixed, Dsa, Dist };

const char* test_name(BoxTestKind t);
const char* order_name(ChildOrder o);
// Throws InputError naming --order and --test when the pair is not allowed
// (dist needs the entry distance of smits).
void check_combination(BoxTestKind t, ChildOrder o);
// The report's name for the configuration (smits-mul-cls, smits-dist,
// smits-dsa, pluecker-cls, pluecker-dsa), else "<test>-<order>".
std::string config_name(BoxTestKind t, ChildOrder o);

// kDsaFirstChild[class][axis]: the child a ray of that class visits first at
// a node split along that axis.
inline constexpr std::array<std::array<std::uint8_t, 3>, 8> kDsaFirstChild = {{
    {0, 0, 0},  // PPP
    {1, 0, 0},  // MPP
    {0, 1, 0},  // PMP
    {1, 1, 0},  // MMP
    {0, 0, 1},  // PPM
    {1, 0, 1},  // MPM
    {0, 1, 1},  // PMM
    {1, 1, 1},  // MMM
}};
inline int dsa_first_child(RayClass c, int axis) { return kDsaFirstChild[c][axis]; }

struct TraversalStats {
    std::uint64_t node_visits = 0;
    std::uint64_t box_tests = 0;
    std::uint64_t tri_tests = 0;
    TraversalStats& operator+=(const TraversalStats& o) {
        node_visits += o.node_visits;
        box_tests += o.box_tests;
        tri_tests += o.tri_tests;
        return *this;
    }
    bool operator==(const TraversalStats&) const = default;
};

// Stack entries a traversal keeps in its frame; deeper BVHs use a
// per-thread heap stack.
inline constexpr int kMaxStack = 256;

// The traversal stack: `local` (kMaxStack entries) when the tree is no
// deeper, else a per-thread buffer grown to the tree's depth.
template <class Entry>
Entry* traversal_stack(Entry* local, int depth) {
    if (depth <= kMaxStack) [[likely]]
        return local;
    thread_local std::vector<Entry> deep;
    if (deep.size() < static_cast<std::size_t>(depth)) deep.resize(static_cast<std::size_t>(depth));
    return deep.data();
}

struct Accel;  // accel.hpp

// Brute force over all triangles with the same triangle test (mesh order).
Hit brute_force_closest(const Mesh& m, const Ray& r);
bool brute_force_any(const Mesh& m, const Ray& r);

// Runtime choice of test and order (one virtual call per ray).
class Tracer {
public:
    virtual ~Tracer() = default;
    virtual Hit closest(const Ray& r, TraversalStats& st) const = 0;
    virtual bool occluded(const Ray& r, TraversalStats& st) const = 0;
};
// Throws InputError for a bad combination (check_combination). The fixed
// test needs a quantised Accel (std::logic_error otherwise). With `record`,
// every box query is appended to it (the tracer is then not thread-safe).
std::unique_ptr<Tracer> make_tracer(const Accel& a, BoxTestKind t, ChildOrder o, std::vector<Query>* record = nullptr);

}  // namespace pluecker
