// SPDX-License-Identifier: MIT
// K-D tree construction (spatial median and binned SAH) and traversal; see
// kdtree.hpp.
#include "pluecker/kdtree.hpp"

#include "pluecker/mesh.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <string>

namespace pluecker {

// ---------------------------------------------------------------------------
// Triangle/box overlap (separating axes)

namespace {

struct D3 {
    double x, y, z;
};
inline D3 sub(const Vec3& a, const D3& c) { return D3{double(a.x) - c.x, double(a.y) - c.y, double(a.z) - c.z}; }
inline D3 sub(const D3& a, const D3& b) { return D3{a.x - b.x, a.y - b.y, a.z - b.z}; }

// Projections p0, p1, p2 against radius r: separated when all lie beyond r
// on one side.
inline bool separated(double p0, double p1, double p2, double r) {
    const double lo = std::min(p0, std::min(p1, p2));
    const double hi = std::max(p0, std::max(p1, p2));
    return lo > r || hi < -r;
}

}  // namespace

bool tri_box_overlap(const Vec3& v0f, const Vec3& v1f, const Vec3& v2f, const Box& box) {
    const D3 c{0.5 * (double(box.lo.x) + double(box.hi.x)), 0.5 * (double(box.lo.y) + double(box.hi.y)),
               0.5 * (double(box.lo.z) + double(box.hi.z))};
    const double big = std::max({1.0, std::fabs(double(box.lo.x)), std::fabs(double(box.lo.y)),
                                 std::fabs(double(box.lo.z)), std::fabs(double(box.hi.x)),
                                 std::fabs(double(box.hi.y)), std::fabs(double(box.hi.z))});
    const double slack = kOverlapSlack * big;
    const D3 h{0.5 * (double(box.hi.x) - double(box.lo.x)) + slack, 0.5 * (double(box.hi.y) - double(box.lo.y)) + slack,
               0.5 * (double(box.hi.z) - double(box.lo.z)) + slack};
    const D3 v0 = sub(v0f, c), v1 = sub(v1f, c), v2 = sub(v2f, c);
    // The 3 box axes: the triangle's bounds against the box.
    if (separated(v0.x, v1.x, v2.x, h.x) || separated(v0.y, v1.y, v2.y, h.y) || separated(v0.z, v1.z, v2.z, h.z))
        return false;
    // The 9 axes e_k x f_j (box axis k, triangle edge f_j).
    const D3 f[3] = {sub(v1, v0), sub(v2, v1), sub(v0, v2)};
    for (const D3& e : f) {
        // x x e = (0, -e.z, e.y)
        if (separated(-e.z * v0.y + e.y * v0.z, -e.z * v1.y + e.y * v1.z, -e.z * v2.y + e.y * v2.z,
                      h.y * std::fabs(e.z) + h.z * std::fabs(e.y)))
            return false;
        // y x e = (e.z, 0, -e.x)
        if (separated(e.z * v0.x - e.x * v0.z, e.z * v1.x - e.x * v1.z, e.z * v2.x - e.x * v2.z,
                      h.x * std::fabs(e.z) + h.z * std::fabs(e.x)))
            return false;
        // z x e = (-e.y, e.x, 0)
        if (separated(-e.y * v0.x + e.x * v0.y, -e.y * v1.x + e.x * v1.y, -e.y * v2.x + e.x * v2.y,
                      h.x * std::fabs(e.y) + h.y * std::fabs(e.x)))
            return false;
    }
    // The triangle's normal: its plane against the box.
    const D3 n{f[0].y * f[1].z - f[0].z * f[1].y, f[0].z * f[1].x - f[0].x * f[1].z,
               f[0].x * f[1].y - f[0].y * f[1].x};
    const double d = n.x * v0.x + n.y * v0.y + n.z * v0.z;
    const double r = h.x * std::fabs(n.x) + h.y * std::fabs(n.y) + h.z * std::fabs(n.z);
    return !(std::fabs(d) > r);
}

// ---------------------------------------------------------------------------
// Options and tree queries

void KdBuildOptions::validate() const {
    auto bad = [](const std::string& field, const std::string& value, const char* expected) {
        throw InputError("KdBuildOptions." + field + ": " + value + " (expected " + expected + ")");
    };
    if (!(std::isfinite(cost_traverse) && cost_traverse >= 0.0f))
        bad("cost_traverse", std::to_string(cost_traverse), "finite, >= 0");
    if (!(std::isfinite(cost_intersect) && cost_intersect > 0.0f))
        bad("cost_intersect", std::to_string(cost_intersect), "finite, > 0");
    if (max_leaf_size < 1) bad("max_leaf_size", std::to_string(max_leaf_size), ">= 1");
    if (bins < 2 || bins > 256) bad("bins", std::to_string(bins), "2..256");
    if (max_depth < 0 || max_depth > kKdMaxDepth) bad("max_depth", std::to_string(max_depth), "0..64");
}

KdBuildOptions KdBuildOptions::from(const BuildOptions& b) {
    KdBuildOptions k;
    k.method = b.method;
    k.cost_traverse = b.cost_traverse;
    k.cost_intersect = b.cost_intersect;
    k.max_leaf_size = b.max_leaf_size;
    return k;
}

std::vector<Box> KdTree::cells() const {
    std::vector<Box> out(nodes.size());
    if (nodes.empty()) return out;
    out[0] = bounds;
    for (std::size_t i = 0; i < nodes.size(); ++i) {  // parents precede their children
        const KdNode& n = nodes[i];
        if (n.is_leaf()) continue;
        Box below = out[i], above = out[i];
        const int a = n.axis();
        below.hi[a] = n.split();
        above.lo[a] = n.split();
        out[i + 1] = below;
        out[n.above()] = above;
    }
    return out;
}

float root_epsilon(const Box& tight) {
    const float big = std::max({1.0f, std::fabs(tight.lo.x), std::fabs(tight.lo.y), std::fabs(tight.lo.z),
                                std::fabs(tight.hi.x), std::fabs(tight.hi.y), std::fabs(tight.hi.z)});
    return 1e-6f * big;
}

// ---------------------------------------------------------------------------
// Build

namespace {

constexpr std::size_t kMaxIndex = std::size_t{1} << 30;

inline float comp(const Vec3& v, int a) { return a == 0 ? v.x : (a == 1 ? v.y : v.z); }

struct Builder {
    const KdBuildOptions& opt;
    int max_depth;
    std::vector<std::array<Vec3, 3>> tv;  // triangle vertices
    std::vector<Box> tb;                  // triangle bounds
    KdTree& out;

    void leaf(std::size_t node, const std::vector<std::uint32_t>& ids) {
        if (out.refs.size() + ids.size() >= kMaxIndex) throw InputError("build_kdtree: more than 2^30 references");
        out.nodes[node] = KdNode::leaf(static_cast<std::uint32_t>(out.refs.size()),
                                       static_cast<std::uint32_t>(ids.size()));
        out.refs.insert(out.refs.end(), ids.begin(), ids.end());
        ++out.leaves;
        if (ids.empty()) ++out.empty_leaves;
    }

    // Distributes ids over the two children of `cell` split at s on axis a.
    void partition(const Box& cell, int a, float s, const std::vector<std::uint32_t>& ids,
                   std::vector<std::uint32_t>& below, std::vector<std::uint32_t>& above) const {
        Box bcell = cell, acell = cell;
        bcell.hi[a] = s;
        acell.lo[a] = s;
        for (const std::uint32_t id : ids) {
            const float lo = comp(tb[id].lo, a), hi = comp(tb[id].hi, a);
            if (hi < s) {
                below.push_back(id);
            } else if (lo > s) {
                above.push_back(id);
            } else {
                const auto& v = tv[id];
                bool l = tri_box_overlap(v[0], v[1], v[2], bcell);
                bool r = tri_box_overlap(v[0], v[1], v[2], acell);
                if (!l && !r) l = r = true;  // rounding: keep it on both sides
                if (l) below.push_back(id);
                if (r) above.push_back(id);
            }
        }
    }

    struct Split {
        int axis = -1;
        float pos = 0.0f;
    };

    Split median_split(const Box& cell, int depth) const {
        for (int k = 0; k < 3; ++k) {
            const int a = (depth + k) % 3;
            const float lo = comp(cell.lo, a), hi = comp(cell.hi, a);
            const float s = 0.5f * (lo + hi);
            if (s > lo && s < hi) return Split{a, s};
        }
        return Split{};
    }

    Split sah_split(const Box& cell, const std::vector<std::uint32_t>& ids) const {
        const int nb = opt.bins;
        const float area = cell.half_area();
        const float n = static_cast<float>(ids.size());
        float best = n * opt.cost_intersect;  // the leaf's cost
        Split out_split;
        std::array<std::uint32_t, 256> lo_count, hi_count;
        std::array<std::uint32_t, 257> right;
        for (int a = 0; a < 3; ++a) {
            const float clo = comp(cell.lo, a), chi = comp(cell.hi, a);
            if (!(chi > clo)) continue;
            const float scale = static_cast<float>(nb) / (chi - clo);
            std::fill(lo_count.begin(), lo_count.begin() + nb, 0u);
            std::fill(hi_count.begin(), hi_count.begin() + nb, 0u);
            auto bin = [&](float x) {
                const int b = static_cast<int>((x - clo) * scale);
                return b < 0 ? 0 : (b >= nb ? nb - 1 : b);
            };
            for (const std::uint32_t id : ids) {
                const float lo = std::max(comp(tb[id].lo, a), clo);
                const float hi = std::min(comp(tb[id].hi, a), chi);
                ++lo_count[static_cast<std::size_t>(bin(lo))];
                ++hi_count[static_cast<std::size_t>(bin(hi))];
            }
            // NR(k) = triangles whose high end is in bin k or above.
            right[static_cast<std::size_t>(nb)] = 0u;
            for (int k = nb - 1; k >= 0; --k)
                right[static_cast<std::size_t>(k)] = right[static_cast<std::size_t>(k) + 1] + hi_count[static_cast<std::size_t>(k)];
            std::uint32_t left = 0;
            const int b1 = (a + 1) % 3, b2 = (a + 2) % 3;
            const float e1 = comp(cell.hi, b1) - comp(cell.lo, b1), e2 = comp(cell.hi, b2) - comp(cell.lo, b2);
            for (int k = 1; k < nb; ++k) {
                left += lo_count[static_cast<std::size_t>(k) - 1];
                const float s = clo + (chi - clo) * (static_cast<float>(k) / static_cast<float>(nb));
                if (!(s > clo && s < chi)) continue;
                const float wl = s - clo, wr = chi - s;
                const float al = e1 * e2 + (e1 + e2) * wl;
                const float ar = e1 * e2 + (e1 + e2) * wr;
                const float nr = static_cast<float>(right[static_cast<std::size_t>(k)]);
                const float cost =
                    opt.cost_traverse + opt.cost_intersect * (al * static_cast<float>(left) + ar * nr) / area;
                if (cost < best) {
                    best = cost;
                    out_split = Split{a, s};
                }
            }
        }
        return out_split;
    }

    void build(std::size_t node, const Box& cell, std::vector<std::uint32_t>& ids, int depth) {
        out.depth = std::max(out.depth, depth + 1);
        const std::size_t n = ids.size();
        Split sp;
        if (depth < max_depth && n > 0) {
            if (opt.method == BuildMethod::Median) {
                if (n > static_cast<std::size_t>(opt.max_leaf_size)) sp = median_split(cell, depth);
            } else {
                sp = sah_split(cell, ids);
            }
        }
        if (sp.axis < 0) {
            leaf(node, ids);
            return;
        }
        std::vector<std::uint32_t> below, above;
        below.reserve(n / 2 + 16);
        above.reserve(n / 2 + 16);
        partition(cell, sp.axis, sp.pos, ids, below, above);
        if (below.size() == n && above.size() == n) {  // no progress: every triangle on both sides
            leaf(node, ids);
            return;
        }
        std::vector<std::uint32_t>().swap(ids);
        Box bcell = cell, acell = cell;
        bcell.hi[sp.axis] = sp.pos;
        acell.lo[sp.axis] = sp.pos;
        out.nodes.emplace_back();
        build(node + 1, bcell, below, depth + 1);
        const std::size_t a = out.nodes.size();
        if (a >= kMaxIndex) throw InputError("build_kdtree: more than 2^30 nodes");
        out.nodes.emplace_back();
        out.nodes[node] = KdNode::interior(sp.axis, sp.pos, static_cast<std::uint32_t>(a));
        build(a, acell, above, depth + 1);
    }
};

}  // namespace

KdTree build_kdtree(std::span<const Vec3> vertices, std::span<const std::array<std::uint32_t, 3>> triangles,
                    const KdBuildOptions& opt) {
    opt.validate();
    const auto t0 = std::chrono::steady_clock::now();
    const std::size_t n = triangles.size();
    if (n == 0) throw InputError("build_kdtree: the mesh has no triangles");
    if (n >= kMaxIndex) throw InputError("build_kdtree: " + std::to_string(n) + " triangles (at most 2^30)");
    KdTree tree;
    int max_depth = opt.max_depth;
    if (max_depth == 0)
        max_depth = static_cast<int>(std::lround(8.0 + 1.3 * std::log2(static_cast<double>(n))));
    max_depth = std::clamp(max_depth, 1, kKdMaxDepth);
    Builder b{opt, max_depth - 1, {}, {}, tree};  // build depth counts from 0
    b.tv.resize(n);
    b.tb.resize(n);
    Box tight;
    for (std::size_t i = 0; i < n; ++i) {
        Box box;
        for (int k = 0; k < 3; ++k) {
            const std::uint32_t vi = triangles[i][static_cast<std::size_t>(k)];
            if (vi >= vertices.size())
                throw InputError("build_kdtree: triangle " + std::to_string(i) + " names vertex " +
                                 std::to_string(vi) + " of " + std::to_string(vertices.size()));
            const Vec3& v = vertices[vi];
            if (!(std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z)))
                throw InputError("build_kdtree: vertex " + std::to_string(vi) + " of triangle " + std::to_string(i) +
                                 " is not finite");
            b.tv[i][static_cast<std::size_t>(k)] = v;
            box.grow(v);
        }
        b.tb[i] = box;
        tight.grow(box);
    }
    const float eps = root_epsilon(tight);
    tree.bounds = Box{tight.lo - Vec3(eps), tight.hi + Vec3(eps)};
    std::vector<std::uint32_t> ids(n);
    for (std::size_t i = 0; i < n; ++i) ids[i] = static_cast<std::uint32_t>(i);
    tree.nodes.reserve(2 * n);
    tree.nodes.emplace_back();
    b.build(0, tree.bounds, ids, 0);
    tree.nodes.shrink_to_fit();
    tree.refs.shrink_to_fit();
    tree.build_ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
    return tree;
}

KdTree build_kdtree(const Mesh& mesh, const KdBuildOptions& opt) {
    return build_kdtree(mesh.vertices, mesh.triangles, opt);
}

// ---------------------------------------------------------------------------
// Traversal

KdAccel::KdAccel(const Mesh& mesh, const KdTree& tree) : nodes(tree.nodes), refs(tree.refs), bounds(tree.bounds) {
    if (nodes.empty()) throw InputError("kd traversal: empty tree");
    tris.resize(mesh.triangles.size());
    for (std::size_t i = 0; i < tris.size(); ++i) {
        const auto& t = mesh.triangles[i];
        tris[i] = LeafTri{mesh.vertices[t[0]], mesh.vertices[t[1]], mesh.vertices[t[2]], static_cast<std::uint32_t>(i)};
    }
    for (const std::uint32_t id : refs)
        if (id >= tris.size()) throw InputError("kd traversal: the tree names triangle " + std::to_string(id));
}

namespace {

// Relative margin of the interval comparisons (kdtree.hpp): many times the
// few ulps of error of a plane distance or a hit distance.
constexpr float kRelMargin = 1e-5f;

template <bool AnyHit>
Hit kd_trace(const KdAccel& a, const Ray& r, TraversalStats& st) {
    const float o[3] = {r.o.x, r.o.y, r.o.z};
    const float d[3] = {r.d.x, r.d.y, r.d.z};
    const float inv[3] = {1.0f / d[0], 1.0f / d[1], 1.0f / d[2]};
    const float lo[3] = {a.bounds.lo.x, a.bounds.lo.y, a.bounds.lo.z};
    const float hi[3] = {a.bounds.hi.x, a.bounds.hi.y, a.bounds.hi.z};
    st.box_tests += 1;
    float t0 = 0.0f, t1 = r.tmax;
    for (int k = 0; k < 3; ++k) {
        float tn = (lo[k] - o[k]) * inv[k], tf = (hi[k] - o[k]) * inv[k];
        if (tn > tf) std::swap(tn, tf);
        t0 = tn > t0 ? tn : t0;  // NaN (origin in a face's plane, d = 0): keep
        t1 = tf < t1 ? tf : t1;
    }
    if (!(t0 <= t1)) return Hit{};
    // Absolute part of the margin: a few float ulps of the scene's
    // coordinates, in units of t.
    const float dl = std::sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
    float scale = 0.0f;
    for (int k = 0; k < 3; ++k) scale = std::max({scale, std::fabs(lo[k]), std::fabs(hi[k]), std::fabs(o[k])});
    const float abs_margin = 1e-6f * scale / dl;
    auto margin = [abs_margin](float t) { return t * kRelMargin + abs_margin; };

    struct Entry {
        std::uint32_t node;
        float tmin, tmax;
    };
    Entry stack[kKdMaxDepth + 1];
    int sp = 0;
    const KdNode* nodes = a.nodes.data();
    const std::uint32_t* refs = a.refs.data();
    const LeafTri* tris = a.tris.data();
    const TriRay tr = tri_setup(r);
    Hit best;
    best.t = r.tmax;
    std::uint64_t visits = 0, tri_tests = 0;
    std::uint32_t cur = 0;
    float tmin = t0, tmax = t1;
    for (;;) {
        ++visits;
        const KdNode n = nodes[cur];
        if (!n.is_leaf()) {
            const int ax = n.axis();
            const float s = n.split();
            const bool below_first = o[ax] < s || (o[ax] == s && d[ax] <= 0.0f);
            const std::uint32_t near = below_first ? cur + 1 : n.above();
            const std::uint32_t far = below_first ? n.above() : cur + 1;
            const float tp = (s - o[ax]) * inv[ax];
            if (tp != tp) {  // the ray lies in the plane: both sides
                stack[sp++] = Entry{far, tmin, tmax};
                cur = near;
                continue;
            }
            if (tp <= 0.0f || tp > tmax + margin(tmax)) {
                cur = near;
                continue;
            }
            if (tp < tmin - margin(tmin)) {
                cur = far;
                continue;
            }
            stack[sp++] = Entry{far, tp > tmin ? tp : tmin, tmax};
            cur = near;
            tmax = tp < tmax ? tp : tmax;
            continue;
        }
        const std::uint32_t end = n.first() + n.count();
        for (std::uint32_t i = n.first(); i < end; ++i) {
            ++tri_tests;
            const LeafTri& tri = tris[refs[i]];
            float t, b1, b2;
            if (tri_intersect(tr, tri.v0, tri.v1, tri.v2, best.t, t, b1, b2) && closer(t, tri.id, best)) {
                best = Hit{t, b1, b2, tri.id};
                if constexpr (AnyHit) goto done;
            }
        }
        if (best.found() && best.t < tmax - margin(tmax)) goto done;
        for (;;) {
            if (sp == 0) goto done;
            const Entry e = stack[--sp];
            if (best.found() && e.tmin - margin(e.tmin) > best.t) continue;
            cur = e.node;
            tmin = e.tmin;
            tmax = e.tmax;
            break;
        }
    }
done:
    st.node_visits += visits;
    st.tri_tests += tri_tests;
    return best.found() ? best : Hit{};
}

class KdTracer final : public Tracer {
public:
    explicit KdTracer(const KdAccel& a) : a_(a) {}
    Hit closest(const Ray& r, TraversalStats& st) const override { return kd_trace<false>(a_, r, st); }
    bool occluded(const Ray& r, TraversalStats& st) const override { return kd_trace<true>(a_, r, st).found(); }

private:
    const KdAccel& a_;
};

}  // namespace

Hit kd_closest(const KdAccel& a, const Ray& r, TraversalStats& st) { return kd_trace<false>(a, r, st); }
bool kd_occluded(const KdAccel& a, const Ray& r, TraversalStats& st) { return kd_trace<true>(a, r, st).found(); }

std::unique_ptr<Tracer> make_kd_tracer(const KdAccel& a) { return std::make_unique<KdTracer>(a); }

}  // namespace pluecker
