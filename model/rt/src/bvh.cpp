// SPDX-License-Identifier: MIT
// BVH construction: spatial median split and binned SAH (see bvh.hpp).
//
// Both builders work on one array of 32-byte primitive records (the
// triangle's bounds) partitioned in place together with Bvh::tri_order, so
// every pass reads memory in order, and on an explicit stack of index
// ranges, so no node allocates. Nodes are reserved up front (a binary tree
// over n triangles has at most 2n - 1 nodes). Boxes stay tight during the
// build; epsilon is applied in one pass at the end.
//
// Boxes are 4-lane vectors (GCC/Clang vector extensions; lane 3 unused), so
// growing a box is one min and one max (`a < b ? a : b` is one minps on
// SSE). Min and max are exact, so every box is the exact float bounds
// whatever the order of the prims.
#include "pluecker/bvh.hpp"

#include "pluecker/mesh.hpp"

#include "records.hpp"

#include <algorithm>
#include <bit>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <memory>

namespace pluecker {
namespace {

typedef float V4 __attribute__((vector_size(16)));
typedef std::int32_t V4i __attribute__((vector_size(16)));

inline V4 vmin(V4 a, V4 b) { return a < b ? a : b; }
inline V4 vmax(V4 a, V4 b) { return a > b ? a : b; }
inline V4 splat(float f) { return V4{f, f, f, f}; }
inline V4 v4(const Vec3& v) { return V4{v.x, v.y, v.z, 0.0f}; }
inline Vec3 vec3(V4 v) { return Vec3(v[0], v[1], v[2]); }

struct VBox {
    V4 lo = splat(kInf);
    V4 hi = splat(-kInf);

    void grow(const VBox& b) {
        lo = vmin(lo, b.lo);
        hi = vmax(hi, b.hi);
    }
    void grow(V4 p) {
        lo = vmin(lo, p);
        hi = vmax(hi, p);
    }
    float half_area() const {
        const V4 e = hi - lo;
        return e[0] * e[1] + e[1] * e[2] + e[2] * e[0];
    }
    Box box() const { return Box{vec3(lo), vec3(hi)}; }
};

// One triangle during the build: its bounds. Centroids are kept doubled
// (lo + hi) to save a multiplication; all centroid bounds are doubled too.
// Lane 3 of lo is +inf, so that binning can count in lane 3 of a bin (see
// Bins); lane 3 of hi holds the prim's half area, computed once for the
// leaf test of sah_node; lane 3 of every other vector is ignored.
struct alignas(32) Prim {
    VBox b;
    V4 centroid2() const { return b.lo + b.hi; }
};
static_assert(sizeof(Prim) == 32);

struct Task {
    VBox cent;  // doubled centroid bounds of the range
    std::int32_t node;
    std::uint32_t begin, end;
    int depth;
};

struct SahSplit {
    float cost = kInf;  // AL*NL + AR*NR
    std::uint32_t imbalance = 0;
    int axis = -1;
    int bin = 0;  // first bin of child 1
};

constexpr int kMaxBins = 64;                                  // one bit each in a uint64 mask
constexpr int kMedianDepthSlack = 256;                       // median: object median from depth 256 + 2*bit_width(n)
constexpr std::uint32_t kSmallNode = 2 * kMaxBins;            // below: one bin set, inline masks
constexpr std::size_t kMaxTriangles = std::size_t{1} << 30;  // 2n - 1 nodes fit int32

int widest_axis(const VBox& b) {
    const V4 e = b.hi - b.lo;
    return e[0] >= e[1] && e[0] >= e[2] ? 0 : (e[1] >= e[2] ? 1 : 2);
}

// Bin mapping of one node: bin = trunc(min((c2 - cmin) * scale, bins - 1))
// per axis, scale = bins / extent of the doubled centroid bounds (0 on a
// flat axis, which maps everything to bin 0).
struct BinMap {
    V4 cmin, scale, top;
    V4i operator()(V4 c2) const { return __builtin_convertvector(vmin((c2 - cmin) * scale, top), V4i); }
};

// Bin bounds per axis. Lane 3 of lo counts the prims in the bin as an
// integer, kCountBias + count: put() takes min(lane 3, +inf), which leaves
// those bits alone, and adds 1 as an integer, so a prim costs one load,
// min/max and store per vector and nothing more. The bias keeps every
// pattern a normal finite float (kCountBias + 2^30 < the bits of +inf), so
// a denormals-are-zero FPU mode cannot touch it.
struct alignas(32) Bins {
    VBox b[3][kMaxBins];

    static constexpr std::uint32_t kCountBias = 0x00800000u;  // FLT_MIN
    static constexpr int kAxisStride = kMaxBins * sizeof(VBox);  // bytes
    static VBox empty() {
        VBox e;
        e.lo[3] = std::bit_cast<float>(kCountBias);
        return e;
    }
    Bins() {
        for (auto& axis : b)
            for (VBox& bin : axis) bin = empty();
    }
    // Byte offsets of a prim's bins on the three axes.
    static_assert(sizeof(VBox) == 32);
    static V4i offsets(V4i k) { return (k << 5) + V4i{0, kAxisStride, 2 * kAxisStride, 0}; }
    void put(int offset, const Prim& p) {
        VBox& bin = *reinterpret_cast<VBox*>(reinterpret_cast<char*>(b) + offset);
        bin.lo = reinterpret_cast<V4>(reinterpret_cast<V4i>(vmin(bin.lo, p.b.lo)) + V4i{0, 0, 0, 1});
        bin.hi = vmax(bin.hi, p.b.hi);
    }
    void put(V4i off, const Prim& p) {
        put(off[0], p);
        put(off[1], p);
        put(off[2], p);
    }
    std::uint32_t count(int a, int k) const {
        return std::bit_cast<std::uint32_t>(b[a][k].lo[3]) - kCountBias;
    }
    // Moves bin (a, k) of `o` into this set and empties it in `o`.
    void take(Bins& o, int a, int k) {
        const std::uint32_t n = count(a, k) + o.count(a, k);
        b[a][k].grow(o.b[a][k]);
        b[a][k].lo[3] = std::bit_cast<float>(kCountBias + n);
        o.b[a][k] = empty();
    }
    std::uint64_t used(int a, int nb) const {
        std::uint64_t u = 0;
        for (int k = 0; k < nb; ++k) u |= std::uint64_t{count(a, k) != 0} << k;
        return u;
    }
};

struct Builder {
    Builder(const BuildOptions& o, Prim* p, std::uint32_t* i, std::vector<BvhNode>& n)
        : opt(o), prims(p), ids(i), nodes(n) {}

    const BuildOptions& opt;
    Prim* prims;
    std::uint32_t* ids;  // Bvh::tri_order, permuted with prims
    std::vector<BvhNode>& nodes;
    std::vector<Task> stack;
    int median_depth_cap = 0;
    // SAH scratch, reused by every node: bin bounds and counts per axis;
    // only bins in `used` are dirty and are reset after each node.
    Bins bins, bins_b;

    void leaf(const Task& t) {
        nodes[t.node].first = static_cast<std::int32_t>(t.begin);
        nodes[t.node].count = static_cast<std::int32_t>(t.end - t.begin);
    }

    // Turns t.node into an interior node over [t.begin, mid) | [mid, t.end)
    // and queues both children (child 0 on top).
    void split(const Task& t, int axis, std::uint32_t mid, const VBox& box0, const VBox& box1,
               const VBox& cent0, const VBox& cent1) {
        const auto c0 = static_cast<std::int32_t>(nodes.size());
        nodes.push_back(BvhNode{box0.box(), 0, 0});
        nodes.push_back(BvhNode{box1.box(), 0, 0});
        nodes[t.node].first = c0;
        nodes[t.node].count = -axis;
        stack.push_back(Task{cent1, c0 + 1, mid, t.end, t.depth + 1});
        stack.push_back(Task{cent0, c0, t.begin, mid, t.depth + 1});
    }

    void swap_prims(std::uint32_t i, std::uint32_t j) {
        std::swap(prims[i], prims[j]);
        std::swap(ids[i], ids[j]);
    }

    // Bounds and centroid bounds of prims[begin, end).
    void bounds(std::uint32_t begin, std::uint32_t end, VBox& box, VBox& cent) const {
        for (std::uint32_t i = begin; i < end; ++i) {
            box.grow(prims[i].b);
            cent.grow(prims[i].centroid2());
        }
    }

    // In-place partition of the task's range (Hoare): prims with left(c2)
    // move to the front. Returns the split index and accumulates the
    // centroid bounds (and, with kBoxes, the bounds) of both sides. The
    // bounds live in locals so that they stay in registers.
    template <bool kBoxes, class Pred>
    std::uint32_t partition(const Task& t, Pred left, VBox& box0, VBox& box1, VBox& cent0,
                            VBox& cent1) {
        V4 b0lo = box0.lo, b0hi = box0.hi, b1lo = box1.lo, b1hi = box1.hi;
        V4 c0lo = cent0.lo, c0hi = cent0.hi, c1lo = cent1.lo, c1hi = cent1.hi;
        std::uint32_t i = t.begin;
        std::uint32_t j = t.end;
        for (;;) {
            V4 ci{}, cj{};
            for (; i < j; ++i) {  // left prims at the front stay
                ci = prims[i].centroid2();
                if (!left(ci)) break;
                if constexpr (kBoxes) b0lo = vmin(b0lo, prims[i].b.lo), b0hi = vmax(b0hi, prims[i].b.hi);
                c0lo = vmin(c0lo, ci);
                c0hi = vmax(c0hi, ci);
            }
            for (; i < j; --j) {  // right prims at the back stay
                cj = prims[j - 1].centroid2();
                if (left(cj)) break;
                if constexpr (kBoxes) b1lo = vmin(b1lo, prims[j - 1].b.lo), b1hi = vmax(b1hi, prims[j - 1].b.hi);
                c1lo = vmin(c1lo, cj);
                c1hi = vmax(c1hi, cj);
            }
            if (i >= j) break;
            // prims[i] belongs right, prims[j - 1] left: swap them.
            if constexpr (kBoxes) {
                b1lo = vmin(b1lo, prims[i].b.lo), b1hi = vmax(b1hi, prims[i].b.hi);
                b0lo = vmin(b0lo, prims[j - 1].b.lo), b0hi = vmax(b0hi, prims[j - 1].b.hi);
            }
            c1lo = vmin(c1lo, ci);
            c1hi = vmax(c1hi, ci);
            c0lo = vmin(c0lo, cj);
            c0hi = vmax(c0hi, cj);
            swap_prims(i++, --j);
        }
        box0 = VBox{b0lo, b0hi};
        box1 = VBox{b1lo, b1hi};
        cent0 = VBox{c0lo, c0hi};
        cent1 = VBox{c1lo, c1hi};
        return i;
    }

    // partition() with a predicate on one lane of the doubled centroid,
    // the lane a compile-time constant: pred(c2[axis]).
    template <bool kBoxes, class Pred>
    std::uint32_t partition_lane(const Task& t, int axis, Pred pred, VBox& box0, VBox& box1,
                                 VBox& cent0, VBox& cent1) {
        switch (axis) {
            case 0: return partition<kBoxes>(t, [&](V4 c) { return pred(c[0]); }, box0, box1, cent0, cent1);
            case 1: return partition<kBoxes>(t, [&](V4 c) { return pred(c[1]); }, box0, box1, cent0, cent1);
            default: return partition<kBoxes>(t, [&](V4 c) { return pred(c[2]); }, box0, box1, cent0, cent1);
        }
    }

    // Object median on `axis`: the smaller half of the centroids goes to
    // child 0. Used when no spatial split separates the triangles.
    void split_object_median(const Task& t, int axis) {
        const std::uint32_t n = t.end - t.begin;
        const std::uint32_t mid = t.begin + n / 2;
        // Sort a permutation, then apply it to prims and ids.
        std::vector<std::uint32_t> perm(n);
        for (std::uint32_t k = 0; k < n; ++k) perm[k] = t.begin + k;
        std::nth_element(perm.begin(), perm.begin() + n / 2, perm.end(),
                         [this, axis](std::uint32_t a, std::uint32_t b) {
                             const float ca = prims[a].centroid2()[axis];
                             const float cb = prims[b].centroid2()[axis];
                             return ca < cb || (ca == cb && a < b);
                         });
        std::vector<Prim> p(n);
        std::vector<std::uint32_t> id(n);
        for (std::uint32_t k = 0; k < n; ++k) {
            p[k] = prims[perm[k]];
            id[k] = ids[perm[k]];
        }
        std::copy(p.begin(), p.end(), prims + t.begin);
        std::copy(id.begin(), id.end(), ids + t.begin);
        VBox box0, box1, cent0, cent1;
        bounds(t.begin, mid, box0, cent0);
        bounds(mid, t.end, box1, cent1);
        split(t, axis, mid, box0, box1, cent0, cent1);
    }

    // The report's median split: the midpoint of the node box on the axes in
    // round-robin order by depth; the next axis when a side stays empty;
    // the object median when all three fail, and below median_depth_cap
    // (where a fan around one vertex has been peeled a triangle per level).
    void median_node(const Task& t) {
        const std::uint32_t n = t.end - t.begin;
        if (n <= static_cast<std::uint32_t>(opt.max_leaf_size)) return leaf(t);
        if (t.depth >= median_depth_cap) return split_object_median(t, t.depth % 3);
        const Box& box = nodes[t.node].box;
        for (int k = 0; k < 3; ++k) {
            const int axis = (t.depth + k) % 3;
            const float mid2 = box.lo[axis] + box.hi[axis];
            VBox box0, box1, cent0, cent1;
            const std::uint32_t mid = partition_lane<true>(
                t, axis, [mid2](float c2) { return c2 < mid2; }, box0, box1, cent0, cent1);
            if (mid != t.begin && mid != t.end) return split(t, axis, mid, box0, box1, cent0, cent1);
        }
        split_object_median(t, t.depth % 3);
    }

    // Bins the range on all three axes; returns the non-empty bins per axis.
    // Large ranges: even and odd prims go to two bin sets, merged at the
    // end, so runs of prims in one bin do not serialise on that bin's
    // memory. Small ranges: one set, and the masks are kept on the way.
    void bin_range(const Task& t, const BinMap& map, std::uint64_t* used) {
        std::uint32_t i = t.begin;
        if (t.end - t.begin < kSmallNode) {
            std::uint64_t u0 = 0, u1 = 0, u2 = 0;
            for (; i < t.end; ++i) {
                const V4i k = map(prims[i].centroid2());
                bins.put(Bins::offsets(k), prims[i]);
                u0 |= std::uint64_t{1} << k[0];
                u1 |= std::uint64_t{1} << k[1];
                u2 |= std::uint64_t{1} << k[2];
            }
            used[0] = u0;
            used[1] = u1;
            used[2] = u2;
            return;
        }
        for (; i + 1 < t.end; i += 2) {
            const V4i k = Bins::offsets(map(prims[i].centroid2()));
            const V4i l = Bins::offsets(map(prims[i + 1].centroid2()));
            bins.put(k, prims[i]);
            bins_b.put(l, prims[i + 1]);
        }
        if (i < t.end) bins.put(Bins::offsets(map(prims[i].centroid2())), prims[i]);
        for (int a = 0; a < 3; ++a) {
            for (std::uint64_t u = bins_b.used(a, opt.bins); u; u &= u - 1)
                bins.take(bins_b, a, std::countr_zero(u));
            used[a] = bins.used(a, opt.bins);
        }
    }

    // Cheapest bin boundary on one axis. Only boundaries between non-empty
    // bins give distinct partitions; each is named by its lowest bin index
    // (`bin` = first bin of child 1 = last non-empty bin of child 0, + 1).
    // Equal costs go to the more balanced split, then to the lower axis/bin.
    void sah_axis(int a, std::uint64_t used, SahSplit& best) const {
        float right_area[kMaxBins];
        std::uint32_t right_n[kMaxBins];
        VBox acc;
        std::uint32_t cnt = 0;
        for (std::uint64_t u = used; u;) {  // child 1 = bins k.. (high to low)
            const int k = 63 - std::countl_zero(u);
            u &= ~(std::uint64_t{1} << k);
            acc.grow(bins.b[a][k]);
            cnt += bins.count(a, k);
            right_area[k] = acc.half_area();
            right_n[k] = cnt;
        }
        acc = VBox{};
        cnt = 0;
        std::uint64_t u = used;
        int k = std::countr_zero(u);
        for (u &= u - 1; u; u &= u - 1) {  // child 0 = bins ..k (low to high)
            acc.grow(bins.b[a][k]);
            cnt += bins.count(a, k);
            const int next = std::countr_zero(u);
            const std::uint32_t rn = right_n[next];
            const float cost = acc.half_area() * static_cast<float>(cnt) +
                               right_area[next] * static_cast<float>(rn);
            if (cost <= best.cost) {
                const std::uint32_t imb = cnt > rn ? cnt - rn : rn - cnt;
                if (cost < best.cost || imb < best.imbalance) best = SahSplit{cost, imb, a, k + 1};
            }
            k = next;
        }
    }

    void clear_bins(const std::uint64_t* used) {
        for (int a = 0; a < 3; ++a)
            for (std::uint64_t u = used[a]; u; u &= u - 1) {
                bins.b[a][std::countr_zero(u)] = Bins::empty();
            }
    }

    // Binned SAH: leaf when the report's cost model prefers it (and the node
    // has at most sah_max_leaf_size triangles), else the cheapest bin
    // boundary over all three axes.
    void sah_node(const Task& t) {
        const std::uint32_t n = t.end - t.begin;
        if (n == 1) return leaf(t);
        const bool may_leaf = n <= static_cast<std::uint32_t>(opt.sah_max_leaf_size);
        const float area = nodes[t.node].box.half_area();
        const float ci = opt.cost_intersect;
        // Cheap leaf test first: every split costs at least
        // cost_traverse*A + cost_intersect*sum(prim areas) (a child's box
        // contains each of its prims' boxes); for two prims that is exact.
        if (may_leaf) {
            float sum = 0.0f;
            for (std::uint32_t i = t.begin; i < t.end; ++i) sum += prims[i].b.hi[3];  // its half area
            if (static_cast<float>(n) * ci * area <= opt.cost_traverse * area + ci * sum) return leaf(t);
        }
        const float nb = static_cast<float>(opt.bins);
        V4 scale{};
        bool any = false;
        for (int a = 0; a < 3; ++a) {
            const float ext = t.cent.hi[a] - t.cent.lo[a];
            const float s = ext > 0.0f ? nb / ext : 0.0f;
            scale[a] = std::isfinite(s) ? s : 0.0f;
            any = any || scale[a] > 0.0f;
        }
        if (!any) {  // all centroids coincide
            if (may_leaf) return leaf(t);
            return split_object_median(t, widest_axis(t.cent));
        }
        const BinMap map{t.cent.lo, scale, splat(nb - 1.0f)};
        std::uint64_t used[3];
        bin_range(t, map, used);
        SahSplit best;
        for (int a = 0; a < 3; ++a)
            if (scale[a] > 0.0f) sah_axis(a, used[a], best);
        const bool leaf_cheaper = best.axis < 0 || static_cast<float>(n) * ci * area <=
                                                       opt.cost_traverse * area + ci * best.cost;
        if (may_leaf && leaf_cheaper) {
            clear_bins(used);
            return leaf(t);
        }
        if (best.axis < 0) {  // cannot happen: a non-flat axis has two non-empty bins
            clear_bins(used);
            return split_object_median(t, widest_axis(t.cent));
        }
        const int a = best.axis;
        VBox box0, box1, cent0, cent1;
        for (std::uint64_t u = used[a]; u; u &= u - 1) {
            const int k = std::countr_zero(u);
            (k < best.bin ? box0 : box1).grow(bins.b[a][k]);
        }
        clear_bins(used);
        // bin < kb exactly when (c2 - cmin) * scale < kb (kb <= bins - 1,
        // same float operations as BinMap).
        const float cmin = map.cmin[a];
        const float s = map.scale[a];
        const auto kb = static_cast<float>(best.bin);
        const std::uint32_t mid = partition_lane<false>(
            t, a, [cmin, s, kb](float c2) { return (c2 - cmin) * s < kb; }, box0, box1, cent0, cent1);
        split(t, a, mid, box0, box1, cent0, cent1);
    }

    void run(BuildMethod method) {
        while (!stack.empty()) {
            const Task t = stack.back();
            stack.pop_back();
            if (method == BuildMethod::Median)
                median_node(t);
            else
                sah_node(t);
        }
    }
};

std::string where_tri(std::size_t i) { return "build_bvh: triangle " + std::to_string(i); }

// Bounds of one triangle, checked: indices in range, vertices finite.
VBox tri_bounds(std::span<const Vec3> v, const std::array<std::uint32_t, 3>& tri, std::size_t i) {
    for (int k = 0; k < 3; ++k)
        if (tri[k] >= v.size())
            throw InputError(where_tri(i) + ": vertex index " + std::to_string(tri[k]) +
                             " out of range (" + std::to_string(v.size()) + " vertices)");
    const V4 a = v4(v[tri[0]]);
    const V4 b = v4(v[tri[1]]);
    const V4 c = v4(v[tri[2]]);
    const V4 s = a + b + c;
    const V4 z = s - s;
    if (!(z[0] == 0.0f && z[1] == 0.0f && z[2] == 0.0f)) {  // inf/NaN (or an overflowing sum)
        for (int k = 0; k < 3; ++k) {
            const Vec3& p = v[tri[k]];
            if (!std::isfinite(p.x) || !std::isfinite(p.y) || !std::isfinite(p.z))
                throw InputError(where_tri(i) + ": vertex " + std::to_string(tri[k]) +
                                 " is not finite");
        }
    }
    V4 lo = vmin(vmin(a, b), c);
    lo[3] = kInf;
    VBox box{lo, vmax(vmax(a, b), c)};
    box.hi[3] = box.half_area();  // see Prim
    return box;
}

}  // namespace

void BuildOptions::validate() const {
    auto bad = [](const std::string& field, const std::string& value, const char* expected) {
        throw InputError("BuildOptions." + field + ": " + value + " (expected " + expected + ")");
    };
    if (!(std::isfinite(epsilon) && epsilon >= 0.0f))
        bad("epsilon", std::to_string(epsilon), "finite, >= 0");
    if (!(std::isfinite(cost_traverse) && cost_traverse >= 0.0f))
        bad("cost_traverse", std::to_string(cost_traverse), "finite, >= 0");
    if (!(std::isfinite(cost_intersect) && cost_intersect > 0.0f))
        bad("cost_intersect", std::to_string(cost_intersect), "finite, > 0");
    if (max_leaf_size < 1) bad("max_leaf_size", std::to_string(max_leaf_size), ">= 1");
    if (sah_max_leaf_size < 1) bad("sah_max_leaf_size", std::to_string(sah_max_leaf_size), ">= 1");
    if (bins < 2 || bins > kMaxBins) bad("bins", std::to_string(bins), "2..64");
}

int Bvh::depth() const {
    if (nodes.empty()) return 0;
    int deepest = 0;
    std::vector<std::pair<std::int32_t, int>> todo{{0, 1}};
    while (!todo.empty()) {
        const auto [i, d] = todo.back();
        todo.pop_back();
        deepest = std::max(deepest, d);
        const BvhNode& node = nodes[static_cast<std::size_t>(i)];
        if (!node.is_leaf()) {
            todo.emplace_back(node.first, d + 1);
            todo.emplace_back(node.first + 1, d + 1);
        }
    }
    return deepest;
}

std::size_t Bvh::leaf_count() const {
    return static_cast<std::size_t>(
        std::count_if(nodes.begin(), nodes.end(), [](const BvhNode& n) { return n.is_leaf(); }));
}

Bvh build_bvh(std::span<const Vec3> vertices, std::span<const std::array<std::uint32_t, 3>> triangles,
              const BuildOptions& opt) {
    const auto t0 = std::chrono::steady_clock::now();
    opt.validate();
    const std::size_t n = triangles.size();
    if (n == 0) throw InputError("build_bvh: the mesh has no triangles");
    if (n > kMaxTriangles)
        throw InputError("build_bvh: " + std::to_string(n) + " triangles (at most 2^30)");

    Bvh bvh;
    bvh.tri_order.resize(n);
    // Raw storage, each record constructed once below (no default fill).
    std::unique_ptr<Prim[], FreeRecords> prims(alloc_records<Prim>(n));  // trivially destructible
    VBox box, cent;
    for (std::size_t i = 0; i < n; ++i) {
        std::construct_at(&prims[i], Prim{tri_bounds(vertices, triangles[i], i)});
        bvh.tri_order[i] = static_cast<std::uint32_t>(i);
        box.grow(prims[i].b);
        cent.grow(prims[i].centroid2());
    }

    bvh.nodes.reserve(2 * n - 1);
    advise_huge(bvh.nodes.data(), bvh.nodes.capacity() * sizeof(BvhNode));
    bvh.nodes.push_back(BvhNode{box.box(), 0, 0});
    auto b = std::make_unique<Builder>(opt, prims.get(), bvh.tri_order.data(), bvh.nodes);
    b->median_depth_cap = kMedianDepthSlack + 2 * std::bit_width(n);
    b->stack.reserve(256);
    b->stack.push_back(Task{cent, 0, 0, static_cast<std::uint32_t>(n), 0});
    b->run(opt.method);

    const Vec3 eps(opt.epsilon);
    for (BvhNode& node : bvh.nodes) {
        node.box.lo = node.box.lo - eps;
        node.box.hi = node.box.hi + eps;
    }
    bvh.build_ms =
        std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
    return bvh;
}

Bvh build_bvh(const Mesh& mesh, const BuildOptions& opt) {
    return build_bvh(std::span<const Vec3>(mesh.vertices),
                     std::span<const std::array<std::uint32_t, 3>>(mesh.triangles), opt);
}

const char* method_name(BuildMethod m) { return m == BuildMethod::Median ? "median" : "sah"; }

}  // namespace pluecker
