// SPDX-License-Identifier: MIT
// BVH traversal: closest hit and any hit over the box tests of boxtest.hpp
// and fixed.hpp, with the child orders of Mahovsky's 2005 report, and a
// batched, resumable traversal for hardware in the loop.
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

#include "pluecker/boxtest.hpp"
#include "pluecker/bvh.hpp"
#include "pluecker/fixed.hpp"
#include "pluecker/geometry.hpp"
#include "pluecker/mesh.hpp"
#include "pluecker/triangle.hpp"
#include "pluecker/vec4.hpp"

#include <glm/common.hpp>


#include <array>
#include <bit>
#include <cmath>
#include <cstddef>
#include <cstdlib>
#include <cstring>
#include <cstdint>
#include <functional>
#include <memory>
#include <optional>
#include <span>
#include <string>
#include <vector>

namespace pluecker {

// ---------------------------------------------------------------------------
// Names and options

enum class BoxTestKind { Exact, Smits, Pluecker, Fixed };
enum class ChildOrder { Fixed, Dsa, Dist };

BoxTestKind parse_box_test(const std::string& s);  // exact|smits|pluecker|fixed, else InputError
const char* test_name(BoxTestKind t);
ChildOrder parse_child_order(const std::string& s);  // fixed|dsa|dist, else InputError
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

// ---------------------------------------------------------------------------
// The layout of the float traversal kernels (smits and pluecker): the two
// children of an interior node in one 64-byte record, their boxes as one
// 4-lane vector per axis, so that both boxes are tested at once.

// A child as the kernels see it: a leaf (count > 0: triangles tris[first,
// first + count)) or an interior node (count <= 0, its children in
// pairs[first]; -count = split axis + 4 * treelet size, see Accel).
struct ChildRef {
    std::int32_t first;
    std::int32_t count;
    bool is_leaf() const { return count > 0; }
    int axis() const { return -count & 3; }
    // Pairs of the treelet this node's pair starts (0: not a treelet root).
    int treelet_size() const { return -count >> 2; }
};

// Levels of the pair layout's treelets (Accel): up to 1 + 2 + 4 pairs.
inline constexpr int kTreeletDepth = 3;

struct alignas(64) NodePair {
    // box[a] = {lo of child 0, lo of child 1, hi of child 0, hi of child 1}
    // on axis a.
    float box[3][4];
    ChildRef child[2];
};
static_assert(sizeof(NodePair) == 64);

// ---------------------------------------------------------------------------
// What a traversal reads: the BVH nodes, the triangles copied in leaf order
// (tris[i] is triangle bvh.tri_order[i]) and, for the fixed-point path, the
// node boxes quantised once.
struct Accel {
    // Copies the nodes (same indices) so that every sibling pair
    // (first, first + 1) shares one 64-byte cache line, and builds the pair
    // layout of the same tree. Large arrays are 2 MiB aligned and asked for
    // transparent huge pages (fewer TLB misses on incoherent rays).
    Accel(const Mesh& mesh, const Bvh& bvh);

    std::span<const BvhNode> nodes;
    int depth = 1;  // levels of the BVH
    std::span<const LeafTri> tris;
    // The same tree for the float kernels: root = nodes[0] as a ChildRef
    // (an interior root names its children's pair). Pairs are laid out in
    // treelets of kTreeletDepth levels: treelets in depth-first order, the
    // pairs of a treelet breadth-first and contiguous, so that a ray
    // entering a treelet (at its root, ChildRef::treelet_size() > 0) fetches
    // all of its lines at once rather than one level at a time.
    ChildRef root{};
    std::span<const NodePair> pairs;
    struct FreeDeleter {
        void operator()(void* p) const { std::free(p); }
    };
    std::unique_ptr<BvhNode[], FreeDeleter> node_store;  // 64-byte aligned; nodes[i] = node_store[i + 1]
    std::unique_ptr<NodePair[], FreeDeleter> pair_store;
    std::unique_ptr<LeafTri[], FreeDeleter> tri_store;

    // Quantises every node box (fixed_quantize_box) for format f.
    void quantize(const FixedFormat& f);
    bool quantized = false;
    FixedFormat format;
    std::vector<FixedBox> qboxes;
};

// ---------------------------------------------------------------------------
// Box tests as traversal policies. Each has a per-ray State, set up once and
// updated when tmax shrinks, and answers hit(state, node index, box).

// Inline forms of smits_hit and pluecker_hit for the traversal loop,
// specialised per ray class C (the report's eight-class form: near and far
// planes and signs are resolved at compile time; the traversal dispatches
// on the class once per ray). They perform the same float operations as
// boxtest.cpp on the same set-up, so they give the same answers (and, for
// smits, the same entry distance). test_traverse.cpp checks the agreement
// on random and extreme queries.
// Component i of v without glm's operator[] (its bounds assert is live in
// -O2 builds without NDEBUG); with a constant i it folds to one load.
[[gnu::always_inline]] inline float at(const Vec3& v, int i) { return i == 0 ? v.x : (i == 1 ? v.y : v.z); }

struct FastSmitsRay {
    Vec3 o, inv;
    float tmax;
};
struct FastPlueckerRay {
    Vec3 o, d, e;  // d: |d_i|
    bool has_end;
};

inline FastSmitsRay fast_smits_setup(const Ray& r) {
    const SmitsRay s = smits_setup(r);
    return FastSmitsRay{s.o, s.inv, s.tmax};
}

template <RayClass C>
[[gnu::always_inline]] inline bool fast_smits_hit(const FastSmitsRay& r, const Box& b, float* tnear) {
    constexpr bool n[3] = {(C & 1) != 0, (C & 2) != 0, (C & 4) != 0};
    float t0 = 0.0f, t1 = r.tmax;
    for (int a = 0; a < 3; ++a) {
        const float en = (at(n[a] ? b.hi : b.lo, a) - at(r.o, a)) * at(r.inv, a);
        const float ex = (at(n[a] ? b.lo : b.hi, a) - at(r.o, a)) * at(r.inv, a);
        t0 = en > t0 ? en : t0;  // NaN (ray inside a plane): keep
        t1 = ex < t1 ? ex : t1;
    }
    if (!(t0 <= t1)) return false;
    if (tnear) *tnear = t0;
    return true;
}

inline FastPlueckerRay fast_pluecker_setup(const Ray& r) {
    const PlueckerRay p = pluecker_setup(r);
    return FastPlueckerRay{p.o, glm::abs(p.d), p.e, p.has_end};
}

template <RayClass C>
[[gnu::always_inline]] inline bool fast_pluecker_hit(const FastPlueckerRay& r, const Box& b) {
    constexpr bool n[3] = {(C & 1) != 0, (C & 2) != 0, (C & 4) != 0};
    float A[3], B[3];
    for (int i = 0; i < 3; ++i) {
        A[i] = n[i] ? at(r.o, i) - at(b.hi, i) : at(b.lo, i) - at(r.o, i);
        B[i] = n[i] ? at(r.o, i) - at(b.lo, i) : at(b.hi, i) - at(r.o, i);
    }
    const float D[3] = {r.d.x, r.d.y, r.d.z};
    // All tests evaluated, one branch at the end: the same conjunction as
    // boxtest.cpp's early returns.
    bool miss = (B[0] < 0.0f) | (B[1] < 0.0f) | (B[2] < 0.0f);
    miss |= B[1] * D[0] - A[0] * D[1] < 0.0f;
    miss |= B[0] * D[1] - A[1] * D[0] < 0.0f;
    miss |= B[2] * D[0] - A[0] * D[2] < 0.0f;
    miss |= B[0] * D[2] - A[2] * D[0] < 0.0f;
    miss |= B[2] * D[1] - A[1] * D[2] < 0.0f;
    miss |= B[1] * D[2] - A[2] * D[1] < 0.0f;
    if (r.has_end)
        for (int i = 0; i < 3; ++i) miss |= (n[i] ? at(b.hi, i) - at(r.e, i) : at(r.e, i) - at(b.lo, i)) < 0.0f;
    return !miss;
}

// Both children of a NodePair at once: the same float operations, per
// lane, as fast_smits_hit and fast_pluecker_hit on each child's box, so the
// same answers (and entry distances). Lanes of a 4-vector (GCC/Clang vector
// extensions; SSE on x86-64) hold {child 0, child 1} twice: for the box
// coordinates {lo, lo, hi, hi}. Bit c of the result is set when child c is
// hit. test_traverse_pairs.cpp checks them against the one-box kernels.

struct SmitsPairRay {
    Float4 o[3];    // o_a in every lane
    Float4 inv[3];  // {1/d_a, 1/d_a, -1/d_a, -1/d_a}
    Float4 init;    // {0, 0, -tmax, -tmax}
};

inline SmitsPairRay smits_pair_setup(const FastSmitsRay& r) {
    SmitsPairRay p;
    for (int a = 0; a < 3; ++a) {
        const float i = at(r.inv, a);
        p.o[a] = splat4(at(r.o, a));
        p.inv[a] = Float4{i, i, -i, -i};
    }
    p.init = Float4{0.0f, 0.0f, -r.tmax, -r.tmax};
    return p;
}

// Lanes 0, 1 accumulate the entry distance t0 of each child, lanes 2, 3 the
// negated exit distance -t1: (far - o) * -inv is exactly -((far - o) * inv),
// and -ex > -t1 exactly when ex < t1, so one max keeps both (a NaN lane
// keeps the old value, as in fast_smits_hit).
template <RayClass C>
[[gnu::always_inline]] inline unsigned fast_smits_pair(const SmitsPairRay& r, const NodePair& p, Float4& tnear) {
    constexpr bool n[3] = {(C & 1) != 0, (C & 2) != 0, (C & 4) != 0};
    Float4 acc = r.init;
    for (int a = 0; a < 3; ++a) {
        const Float4 b = load4(p.box[a]);
        const Float4 v = ((n[a] ? swap_halves(b) : b) - r.o[a]) * r.inv[a];  // {en, en, -ex, -ex}
        acc = v > acc ? v : acc;
    }
    tnear = acc;  // lanes 0, 1
    return lane_bits(acc <= -swap_halves(acc)) & 3u;
}

struct PlueckerPairRay {
    Float4 o[3];   // o_a in every lane
    Float4 e[3];   // segment end e_a in every lane
    Float4 dv[3];  // cross tests (i, j) = (0,1), (0,2), (1,2): {D_i, D_i, D_j, D_j}
    Float4 du[3];  //                                          {D_j, D_j, D_i, D_i}
    bool has_end;
};

inline PlueckerPairRay pluecker_pair_setup(const FastPlueckerRay& r) {
    PlueckerPairRay p;
    for (int a = 0; a < 3; ++a) {
        p.o[a] = splat4(at(r.o, a));
        p.e[a] = splat4(at(r.e, a));
    }
    constexpr int ij[3][2] = {{0, 1}, {0, 2}, {1, 2}};
    for (int k = 0; k < 3; ++k) {
        const float di = at(r.d, ij[k][0]), dj = at(r.d, ij[k][1]);
        p.dv[k] = Float4{di, di, dj, dj};
        p.du[k] = Float4{dj, dj, di, di};
    }
    p.has_end = r.has_end;
    return p;
}

// W[a] = {A_a, A_a, B_a, B_a} (children 0, 1). Lanes 0, 1 of the result:
// B_j*D_i - A_i*D_j < 0; lanes 2, 3: B_i*D_j - A_j*D_i < 0.
template <int I, int J>
[[gnu::always_inline]] inline Int4 pluecker_cross_miss(const Float4* W, Float4 dv, Float4 du) {
    const Float4 b = __builtin_shufflevector(W[J], W[I], 2, 3, 6, 7);  // {B_j, B_j, B_i, B_i}
    const Float4 a = __builtin_shufflevector(W[I], W[J], 0, 1, 4, 5);  // {A_i, A_i, A_j, A_j}
    return b * dv - a * du < Float4{};
}

template <RayClass C>
[[gnu::always_inline]] inline unsigned fast_pluecker_pair(const PlueckerPairRay& r, const NodePair& p) {
    constexpr bool n[3] = {(C & 1) != 0, (C & 2) != 0, (C & 4) != 0};
    const Float4 zero{};
    Float4 bx[3], W[3];
    for (int a = 0; a < 3; ++a) {
        bx[a] = load4(p.box[a]);
        W[a] = n[a] ? swap_halves(r.o[a] - bx[a]) : bx[a] - r.o[a];
    }
    // Origin test (lanes 2, 3: B < 0), then the six silhouette tests.
    Int4 miss = ((W[0] < zero) | (W[1] < zero) | (W[2] < zero)) & Int4{0, 0, -1, -1};
    miss |= pluecker_cross_miss<0, 1>(W, r.dv[0], r.du[0]);
    miss |= pluecker_cross_miss<0, 2>(W, r.dv[1], r.du[1]);
    miss |= pluecker_cross_miss<1, 2>(W, r.dv[2], r.du[2]);
    if (r.has_end) {  // lanes 0, 1: e - lo (positive axis) or hi - e (negative)
        Int4 end{};
        for (int a = 0; a < 3; ++a) end |= (n[a] ? swap_halves(bx[a] - r.e[a]) : r.e[a] - bx[a]) < zero;
        miss |= end & Int4{-1, -1, 0, 0};
    }
    const unsigned bits = lane_bits(miss);
    return ~(bits | bits >> 2) & 3u;
}

// A policy's hit<C>(state, node, box, tnear) may use the class C of the ray
// (the traversal passes the class of the ray it set up).
// A policy with kPairs also answers hit2<C>(state, pair, tnear): the bits
// of the children of a NodePair it hits (traverse_pairs); with kDistance
// their entry distances in lanes 0, 1 of tnear.
struct SmitsPolicy {
    static constexpr bool kDistance = true;
    static constexpr bool kPairs = true;
    struct State {
        FastSmitsRay s;
        Ray ray;
        SmitsPairRay pr;
    };
    State setup(const Ray& r) const {
        const FastSmitsRay s = fast_smits_setup(r);
        return {s, r, smits_pair_setup(s)};
    }
    bool live(const State&) const { return true; }
    void shrink(State& st, float t) const {
        st.s.tmax = t;
        st.ray.tmax = t;
        st.pr.init = Float4{0.0f, 0.0f, -t, -t};
    }
    template <RayClass C>
    [[gnu::always_inline]] bool hit(const State& st, std::uint32_t, const Box& b, float* tnear) const {
        return fast_smits_hit<C>(st.s, b, tnear);
    }
    template <RayClass C>
    [[gnu::always_inline]] unsigned hit2(const State& st, const NodePair& p, Float4& tnear) const {
        return fast_smits_pair<C>(st.pr, p, tnear);
    }
    Ray query_ray(const State& st) const { return st.ray; }
};

struct PlueckerPolicy {
    static constexpr bool kDistance = false;
    static constexpr bool kPairs = true;
    struct State {
        FastPlueckerRay p;
        Ray ray;
        PlueckerPairRay pr;
    };
    State setup(const Ray& r) const {
        const FastPlueckerRay p = fast_pluecker_setup(r);
        return {p, r, pluecker_pair_setup(p)};
    }
    bool live(const State&) const { return true; }
    void shrink(State& st, float t) const {
        st.ray.tmax = t;
        st.p = fast_pluecker_setup(st.ray);
        st.pr = pluecker_pair_setup(st.p);
    }
    template <RayClass C>
    [[gnu::always_inline]] bool hit(const State& st, std::uint32_t, const Box& b, float*) const {
        return fast_pluecker_hit<C>(st.p, b);
    }
    template <RayClass C>
    [[gnu::always_inline]] unsigned hit2(const State& st, const NodePair& p, Float4&) const {
        return fast_pluecker_pair<C>(st.pr, p);
    }
    Ray query_ray(const State& st) const { return st.ray; }
};

struct ExactPolicy {
    static constexpr bool kDistance = false;
    struct State {
        Ray ray;
    };
    State setup(const Ray& r) const { return {r}; }
    bool live(const State&) const { return true; }
    void shrink(State& st, float t) const { st.ray.tmax = t; }
    template <RayClass>
    bool hit(const State& st, std::uint32_t, const Box& b, float*) const {
        return exact_hit(st.ray, b);
    }
    Ray query_ray(const State& st) const { return st.ray; }
};

struct FixedPolicy {
    static constexpr bool kDistance = false;
    explicit FixedPolicy(const Accel& a) : accel(&a) {}
    const Accel* accel;
    struct State {
        Ray ray;  // the ray as given, tmax shrunk to the best hit
        FixedRay fr;
        bool live = false;
    };
    State setup(const Ray& r) const;
    bool live(const State& st) const { return st.live; }
    void shrink(State& st, float t) const;
    template <RayClass>
    bool hit(const State& st, std::uint32_t node, const Box&, float*) const {
        return fixed_hit(st.fr, accel->qboxes[node], accel->format);
    }
    Ray query_ray(const State& st) const { return st.ray; }
};

// Wraps a policy and appends every query it answers to *out.
template <class Inner>
struct RecordingPolicy {
    static constexpr bool kDistance = Inner::kDistance;
    const Inner* inner;
    std::vector<Query>* out;
    using State = typename Inner::State;
    State setup(const Ray& r) const { return inner->setup(r); }
    bool live(const State& st) const { return inner->live(st); }
    void shrink(State& st, float t) const { inner->shrink(st, t); }
    template <RayClass C>
    bool hit(const State& st, std::uint32_t node, const Box& b, float* tnear) const {
        out->push_back(Query{inner->query_ray(st), b});
        return inner->template hit<C>(st, node, b, tnear);
    }
    Ray query_ray(const State& st) const { return inner->query_ray(st); }
};

// ---------------------------------------------------------------------------
// The traversal loop for rays of class C.

[[gnu::always_inline]] inline void prefetch_below(const Accel& a, const BvhNode& n) {
    const void* p = n.is_leaf() ? static_cast<const void*>(a.tris.data() + n.first)
                                : static_cast<const void*>(a.nodes.data() + n.first);
    __builtin_prefetch(p);
}

template <class Policy, ChildOrder Order, bool AnyHit, RayClass C>
Hit traverse_class(const Accel& a, const Policy& test, const Ray& ray, TraversalStats& st) {
    static_assert(Order != ChildOrder::Dist || Policy::kDistance, "dist order needs the entry distance");
    struct Entry {
        std::uint32_t node;
        float tnear;
    };
    auto s = test.setup(ray);
    if (!test.live(s)) return Hit{};
    const BvhNode* nodes = a.nodes.data();
    const LeafTri* tris = a.tris.data();
    const TriRay tr = tri_setup(ray);
    Hit best;
    best.t = ray.tmax;
    Entry local[kMaxStack];
    Entry* const stack = traversal_stack(local, a.depth);
    int sp = 0;
    float tn0 = 0.0f, tn1 = 0.0f;
    // Counters in locals: the compiler keeps them in registers.
    std::uint64_t visits = 0, boxes = 1, tri_tests = 0;
    std::uint32_t cur = 0;
    if (!test.template hit<C>(s, 0, nodes[0].box, &tn0)) goto done;
    for (;;) {
        ++visits;
        {
            const BvhNode& n = nodes[cur];
            if (n.is_leaf()) {
                const float before = best.t;
                const std::uint32_t end = static_cast<std::uint32_t>(n.first + n.count);
                for (std::uint32_t i = static_cast<std::uint32_t>(n.first); i < end; ++i) {
                    ++tri_tests;
                    const LeafTri& tri = tris[i];
                    float t, b1, b2;
                    if (tri_intersect(tr, tri.v0, tri.v1, tri.v2, best.t, t, b1, b2) && closer(t, tri.id, best)) {
                        best = Hit{t, b1, b2, tri.id};
                        if constexpr (AnyHit) goto done;
                    }
                }
                if (best.t < before) test.shrink(s, best.t);
            } else {
                const std::uint32_t c0 = static_cast<std::uint32_t>(n.first);
                boxes += 2;
                // Both children's data (their child pair or their triangles)
                // is fetched while the boxes are tested: one level of memory
                // latency hidden on rays that leave the cache.
                prefetch_below(a, nodes[c0]);
                prefetch_below(a, nodes[c0 + 1]);
                const bool h0 = test.template hit<C>(s, c0, nodes[c0].box, &tn0);
                const bool h1 = test.template hit<C>(s, c0 + 1, nodes[c0 + 1].box, &tn1);
                if (h0 && h1) {
                    bool swap;
                    if constexpr (Order == ChildOrder::Fixed)
                        swap = false;
                    else if constexpr (Order == ChildOrder::Dsa)
                        swap = dsa_first_child(C, n.axis()) != 0;
                    else
                        swap = tn1 < tn0;
                    stack[sp++] = swap ? Entry{c0, tn0} : Entry{c0 + 1, tn1};
                    cur = swap ? c0 + 1 : c0;
                    continue;
                }
                if (h0 || h1) {
                    cur = h0 ? c0 : c0 + 1;
                    continue;
                }
            }
        }
        for (;;) {
            if (sp == 0) goto done;
            const Entry e = stack[--sp];
            if constexpr (Order == ChildOrder::Dist) {
                if (e.tnear > best.t) continue;
            }
            cur = e.node;
            break;
        }
    }
done:
    st.node_visits += visits;
    st.box_tests += boxes;
    st.tri_tests += tri_tests;
    return best.found() ? best : Hit{};
}

// The triangles tris[0, count) of one leaf, in order, with the test
// specialised for the ray's shear axes (tri_intersect_packed). Returns true
// when an any-hit search may stop; `tested` counts the triangles tested.
// One out-of-line copy per (KZ, SWAP): the traversal picks it once per ray
// (leaf_fn) and calls it through a pointer, which predicts well.
template <int KZ, bool SWAP, bool AnyHit>
[[gnu::noinline]] bool leaf_hits(const TriRay& tr, const LeafTri* t, std::int32_t count, Hit& best,
                                 std::uint64_t& tested) {
    const LeafTri* end = t + count;
    for (; t != end; ++t) {
        float th, b1, b2;
        if (tri_intersect_packed<KZ, SWAP>(tr, *t, best.t, th, b1, b2) && closer(th, t->id, best)) {
            best = Hit{th, b1, b2, t->id};
            if constexpr (AnyHit) {
                tested += static_cast<std::uint64_t>(t - end + count + 1);
                return true;
            }
        }
    }
    tested += static_cast<std::uint64_t>(count);
    return false;
}

template <bool AnyHit>
using LeafFn = bool (*)(const TriRay&, const LeafTri*, std::int32_t, Hit&, std::uint64_t&);

template <bool AnyHit>
LeafFn<AnyHit> leaf_fn(const TriRay& tr) {
    static constexpr LeafFn<AnyHit> kFns[3][2] = {
        {leaf_hits<0, false, AnyHit>, leaf_hits<0, true, AnyHit>},
        {leaf_hits<1, false, AnyHit>, leaf_hits<1, true, AnyHit>},
        {leaf_hits<2, false, AnyHit>, leaf_hits<2, true, AnyHit>},
    };
    return kFns[tr.kz][tr.kx != (tr.kz + 1) % 3 ? 1 : 0];
}

template <class Policy>
inline constexpr bool kHasPairs = requires { requires Policy::kPairs; };

// The same traversal over Accel::pairs for a policy with kPairs: both
// children of a node tested by one hit2 call. Visits the same nodes in the
// same order, counts the same and returns the same hit as traverse_class.
template <class Policy, ChildOrder Order, bool AnyHit, RayClass C>
Hit traverse_pairs(const Accel& a, const Policy& test, const Ray& ray, TraversalStats& st) {
    static_assert(Order != ChildOrder::Dist || Policy::kDistance, "dist order needs the entry distance");
    struct Entry {
        ChildRef ref;
        float tnear;
    };
    auto s = test.setup(ray);
    const NodePair* pairs = a.pairs.data();
    const LeafTri* tris = a.tris.data();
    const TriRay tr = tri_setup(ray);
    const LeafFn<AnyHit> leaf = leaf_fn<AnyHit>(tr);
    Hit best;
    best.t = ray.tmax;
    Entry local[kMaxStack];
    Entry* const stack = traversal_stack(local, a.depth);
    int sp = 0;
    // Counters in registers; box tests = 1 (the root) + 2 per interior node
    // visited, taken from the visits and the leaf visits at the end.
    std::uint64_t visits = 0, leaves = 0, tri_tests = 0;
    ChildRef cur = a.root;
    {
        float t0;
        if (!test.template hit<C>(s, 0, a.nodes[0].box, &t0)) goto done;
    }
    for (;;) {
        ++visits;
        if (cur.is_leaf()) {
            ++leaves;
            const float before = best.t;
            if (leaf(tr, tris + cur.first, cur.count, best, tri_tests)) goto done;
            if (best.t < before) test.shrink(s, best.t);
        } else {
            const NodePair& p = pairs[cur.first];
            // Entering a treelet: its other pairs are fetched now. (Fetching
            // both children's pair or triangles here as well made camera
            // rays 8% slower: most of those lines are not needed, and they
            // compete with the ones that are.)
            for (int k = 1; k < cur.treelet_size(); ++k) __builtin_prefetch(&p + k);
            Float4 tn;
            const unsigned hit = test.template hit2<C>(s, p, tn);
            // Branches on the hit mask, not a computed index: the next
            // node's address is then predicted, and its loads start before
            // the test ends. The order of two hit children is a select.
            if (hit == 3u) {
                bool swap;
                if constexpr (Order == ChildOrder::Fixed)
                    swap = false;
                else if constexpr (Order == ChildOrder::Dsa)
                    swap = dsa_first_child(C, cur.axis()) != 0;
                else
                    swap = tn[1] < tn[0];
                constexpr bool kDist = Order == ChildOrder::Dist;
                const auto r0 = std::bit_cast<std::uint64_t>(p.child[0]);
                const auto r1 = std::bit_cast<std::uint64_t>(p.child[1]);
                const std::uint64_t near_ref = swap ? r1 : r0, far_ref = swap ? r0 : r1;
                const float far_t = kDist ? (swap ? tn[0] : tn[1]) : 0.0f;
                stack[sp++] = Entry{std::bit_cast<ChildRef>(far_ref), far_t};
                cur = std::bit_cast<ChildRef>(near_ref);
                continue;
            }
            if (hit == 1u) {
                cur = p.child[0];
                continue;
            }
            if (hit == 2u) {
                cur = p.child[1];
                continue;
            }
        }
        for (;;) {
            if (sp == 0) goto done;
            --sp;
            if constexpr (Order == ChildOrder::Dist) {
                if (stack[sp].tnear > best.t) continue;
            }
            cur = stack[sp].ref;
            break;
        }
    }
done:
    st.node_visits += visits;
    st.box_tests += 1 + 2 * (visits - leaves);
    st.tri_tests += tri_tests;
    return best.found() ? best : Hit{};
}

// The traversal. Returns the closest hit (AnyHit = false) or the first hit
// found (AnyHit = true) with 0 <= t <= ray.tmax; Hit{} when none. Policies
// with kPairs take traverse_pairs, the others traverse_class.
template <class Policy, ChildOrder Order, bool AnyHit, RayClass C>
Hit traverse_any(const Accel& a, const Policy& test, const Ray& ray, TraversalStats& st) {
    if constexpr (kHasPairs<Policy>)
        return traverse_pairs<Policy, Order, AnyHit, C>(a, test, ray, st);
    else
        return traverse_class<Policy, Order, AnyHit, C>(a, test, ray, st);
}

template <class Policy, ChildOrder Order, bool AnyHit>
Hit traverse(const Accel& a, const Policy& test, const Ray& ray, TraversalStats& st) {
    switch (ray_class(ray.d)) {
        case 0: return traverse_any<Policy, Order, AnyHit, 0>(a, test, ray, st);
        case 1: return traverse_any<Policy, Order, AnyHit, 1>(a, test, ray, st);
        case 2: return traverse_any<Policy, Order, AnyHit, 2>(a, test, ray, st);
        case 3: return traverse_any<Policy, Order, AnyHit, 3>(a, test, ray, st);
        case 4: return traverse_any<Policy, Order, AnyHit, 4>(a, test, ray, st);
        case 5: return traverse_any<Policy, Order, AnyHit, 5>(a, test, ray, st);
        case 6: return traverse_any<Policy, Order, AnyHit, 6>(a, test, ray, st);
        default: return traverse_any<Policy, Order, AnyHit, 7>(a, test, ray, st);
    }
}

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

// ---------------------------------------------------------------------------
// Batched, resumable fixed-point traversal (hardware in the loop).
//
// A ray is a state machine: it emits the box queries it needs (the root box,
// then the two child boxes of each interior node it enters), waits for their
// answers, and continues. A driver keeps many rays in flight, gathers their
// queries into one batch and hands the batch to a BoxEngine: the software
// engine calls fixed_hit, the Verilator harness in sim/ sends the same
// queries through the RTL. Given the same answers, the batched traversal
// issues the same queries per ray, visits the same nodes and returns the
// same hit as traverse<FixedPolicy, ...>.

// One ray/box query as the RTL takes it, plus its float form.
struct BoxQuery {
    Query query;         // the ray as given (tmax as the test sees it) and the node's float box
    FixedRay ray;        // *fixed_setup_ray(query.ray, format)
    FixedBox box;        // fixed_quantize_box(query.box, format)
    std::uint32_t node;  // BVH node index of the box
};

class BoxEngine {
public:
    virtual ~BoxEngine() = default;
    // Answers a whole batch: hits[i] = 1 when batch[i] hits, else 0.
    // hits.size() == batch.size() >= 1.
    virtual void test(std::span<const BoxQuery> batch, std::span<std::uint8_t> hits) = 0;
};

// The software engine: fixed_hit on every query.
class SoftwareBoxEngine final : public BoxEngine {
public:
    explicit SoftwareBoxEngine(const FixedFormat& f) : format_(f) {}
    void test(std::span<const BoxQuery> batch, std::span<std::uint8_t> hits) override;

private:
    FixedFormat format_;
};

// One ray's resumable traversal. The Accel must be quantised.
class RayTraversal {
public:
    RayTraversal(const Accel& a, ChildOrder o);  // o: fixed or dsa
    // Starts a ray; afterwards either done() or pending() is non-empty.
    void start(const Ray& r, bool any_hit);
    bool done() const { return done_; }
    // The queries awaiting answers (1 for the root, 2 for a node's children).
    std::span<const BoxQuery> pending() const { return {queries_.data(), done_ ? 0u : pending_}; }
    // Answers to pending(), in order. Tests the triangles of the leaves it
    // reaches and stops at the next interior node or when done.
    void resume(std::span<const std::uint8_t> hits);
    // Closest (or any) hit; valid when done(). Hit{} when none.
    Hit hit() const { return best_.found() ? best_ : Hit{}; }
    const TraversalStats& stats() const { return stats_; }

private:
    void emit(std::uint32_t node, std::size_t slot);
    void advance(std::uint32_t node);
    bool pop(std::uint32_t& node);

    const Accel* accel_;
    ChildOrder order_;
    FixedPolicy policy_;
    FixedPolicy::State state_;
    TriRay tri_{};
    RayClass cls_ = 0;
    bool any_hit_ = false;
    bool done_ = true;
    Hit best_;
    TraversalStats stats_;
    std::uint32_t node_ = 0;  // the node whose children are pending
    bool root_pending_ = false;
    std::uint32_t pending_ = 0;
    std::array<BoxQuery, 2> queries_{};
    std::vector<std::uint32_t> stack_;
};

// A ray handed to the driver, and its answer.
struct BatchRay {
    Ray ray;
    bool any_hit = false;
    std::uint64_t tag = 0;  // the caller's handle, returned with the result
};
struct BatchResult {
    std::uint64_t tag;
    Hit hit;
};

struct BatchStats {
    std::uint64_t batches = 0;
    std::uint64_t queries = 0;
    std::size_t max_batch = 0;
};

// The driver. Keeps up to `pool` rays in flight: asks next() for a ray
// whenever a slot is free (next returns false when it has none right now;
// the driver stops when it returns false and no ray is in flight), gathers
// the pending queries of all rays in slot order into one batch per round,
// calls engine.test once per round, and calls finish() for every ray that
// completes (in slot order). finish() may make new rays available to next().
void run_batched(const Accel& a, ChildOrder o, BoxEngine& engine, std::size_t pool,
                 const std::function<bool(BatchRay&)>& next, const std::function<void(const BatchResult&)>& finish,
                 TraversalStats& st, BatchStats* bs = nullptr);

// Convenience: traces a list of rays; result i belongs to rays[i].
std::vector<Hit> trace_batched(const Accel& a, ChildOrder o, BoxEngine& engine, std::size_t pool,
                               std::span<const Ray> rays, bool any_hit, TraversalStats& st);

}  // namespace pluecker
