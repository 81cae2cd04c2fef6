// SPDX-License-Identifier: MIT
#include "pluecker/render.hpp"

#include "pluecker/query.hpp"

#include <glm/geometric.hpp>
#include <glm/trigonometric.hpp>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <deque>
#include <ostream>
#include <stdexcept>
#include <thread>
#include <unordered_map>

namespace pluecker {

const char* ray_kind_name(RayKind k) {
    switch (k) {
        case RayKind::Camera: return "camera";
        case RayKind::Shadow: return "shadow";
        case RayKind::Reflection: return "reflection";
        case RayKind::Refraction: return "refraction";
    }
    return "?";
}

// ---------------------------------------------------------------------------
// Camera and lights

namespace {

// From the centre towards the eye (Y is up in every built-in scene), and a
// distance factor: 1 fits the bounding sphere into the view; the spheres'
// floor reaches far out, so that view comes closer.
struct View {
    Vec3 dir;
    float distance;
};
View scene_view(const std::string& name) {
    if (name == "teapot") return {Vec3(0.45f, 0.55f, 1.0f), 0.95f};
    if (name == "spheres") return {Vec3(0.0f, 0.55f, 1.0f), 0.62f};
    return {Vec3(0.35f, 0.45f, 1.0f), 1.0f};
}

}  // namespace

Camera default_camera(const Mesh& m) {
    const Box b = m.bounds();
    const Vec3 c = b.empty() ? Vec3(0.0f) : b.center();
    float r = 0.0f;
    for (const Vec3& v : m.vertices) r = std::max(r, glm::length(v - c));
    if (r <= 0.0f) r = 1.0f;
    Camera cam;
    cam.look = c;
    cam.fov_deg = 40.0f;
    const float half = glm::radians(cam.fov_deg) * 0.5f;
    const View view = scene_view(m.name);
    cam.eye = c + glm::normalize(view.dir) * (view.distance * r / std::sin(half));
    return cam;
}

CameraBasis camera_basis(const Camera& c) {
    CameraBasis b;
    b.w = glm::normalize(c.eye - c.look);
    b.side = glm::cross(c.up, b.w);
    b.u = glm::normalize(b.side);
    b.v = glm::cross(b.w, b.u);
    return b;
}

std::vector<Light> default_lights(const Camera& c, int count) {
    const auto [w, side, u, v] = camera_basis(c);
    const float dist = glm::length(c.eye - c.look);
    std::vector<Light> lights;
    // Key light above and to the right of the camera, fill light low left.
    lights.push_back({c.eye + dist * (0.9f * u + 1.1f * v + 0.2f * w), Vec3(0.85f, 0.82f, 0.78f)});
    if (count >= 2) lights.push_back({c.eye + dist * (-1.2f * u + 0.2f * v), Vec3(0.25f, 0.28f, 0.33f)});
    return lights;
}

RenderScene::RenderScene(const Mesh& m, const Accel& a) : mesh(m), accel(a), normals(m.vertices.size(), Vec3(0.0f)) {
    for (const auto& t : m.triangles) {
        const Vec3 n = glm::cross(m.vertices[t[1]] - m.vertices[t[0]], m.vertices[t[2]] - m.vertices[t[0]]);
        for (int k = 0; k < 3; ++k) normals[t[k]] += n;
    }
    for (Vec3& n : normals) {
        const float l = glm::length(n);
        n = l > 0.0f ? n / l : Vec3(0.0f);
    }
}

// ---------------------------------------------------------------------------
// Ray trees

namespace {

constexpr float kOffset = 1e-4f;

struct RayNode {
    Ray ray;
    Vec3 weight{1.0f};  // contribution to the parent
    Vec3 tint{0.0f};    // set by expand(): material colour
    float base = 0.0f;  // set by expand(): ambient term
    std::int32_t first_child = -1;
    std::uint8_t n_children = 0;
    RayKind kind = RayKind::Camera;
    std::uint8_t depth = 0;
    bool inside = false;  // travelling inside glass
    Hit hit;              // closest-hit kinds
    bool occluded = false;  // shadow rays
};

using PixelTree = std::vector<RayNode>;

struct Shader {
    Shader(const RenderScene& s, const RenderOptions& o) : scene(s), opts(o) {
        cam = o.camera ? *o.camera : default_camera(s.mesh);
        lights = o.lights.empty() ? default_lights(cam, o.light_count) : o.lights;
        const CameraBasis b = camera_basis(cam);
        w = b.w;
        u = b.u;
        v = b.v;
        tan_half = std::tan(glm::radians(cam.fov_deg) * 0.5f);
        aspect = static_cast<float>(o.width) / static_cast<float>(o.height);
    }

    Ray camera_ray(int x, int y) const {
        const float sx = (2.0f * (static_cast<float>(x) + 0.5f) / static_cast<float>(opts.width) - 1.0f) * tan_half * aspect;
        const float sy = (1.0f - 2.0f * (static_cast<float>(y) + 0.5f) / static_cast<float>(opts.height)) * tan_half;
        Ray r;
        r.o = cam.eye;
        r.d = glm::normalize(sx * u + sy * v - w);
        r.tmax = kInf;
        return r;
    }

    static void start(PixelTree& tree, const Ray& r) {
        tree.clear();
        RayNode n;
        n.ray = r;
        n.kind = RayKind::Camera;
        tree.push_back(n);
    }

    static RayNode child(const RayNode& parent, RayKind kind, const Vec3& o, const Vec3& d, float tmax,
                         const Vec3& weight, bool inside) {
        RayNode c;
        c.ray = Ray{o, d, tmax};
        c.kind = kind;
        c.weight = weight;
        c.depth = static_cast<std::uint8_t>(parent.depth + (kind == RayKind::Shadow ? 0 : 1));
        c.inside = inside;
        return c;
    }

    // Makes the children of tree[i] from its hit (its result must be set).
    void expand(PixelTree& tree, std::size_t i) const {
        const RayNode n = tree[i];
        if (n.kind == RayKind::Shadow || !n.hit.found()) return;
        const auto& tri = scene.mesh.triangles[n.hit.tri];
        const Vec3& p0 = scene.mesh.vertices[tri[0]];
        const Vec3& p1 = scene.mesh.vertices[tri[1]];
        const Vec3& p2 = scene.mesh.vertices[tri[2]];
        const float b0 = 1.0f - n.hit.b1 - n.hit.b2;
        const Vec3 p = b0 * p0 + n.hit.b1 * p1 + n.hit.b2 * p2;
        const Vec3 dir = glm::normalize(n.ray.d);
        Vec3 ng = glm::cross(p1 - p0, p2 - p0);
        const float ngl = glm::length(ng);
        ng = ngl > 0.0f ? ng / ngl : -dir;
        if (glm::dot(ng, dir) > 0.0f) ng = -ng;  // faces the incoming ray
        Vec3 ns = b0 * scene.normals[tri[0]] + n.hit.b1 * scene.normals[tri[1]] + n.hit.b2 * scene.normals[tri[2]];
        const float nsl = glm::length(ns);
        ns = nsl > 1e-6f ? ns / nsl : ng;
        if (glm::dot(ns, ng) < 0.0f) ns = -ns;
        const std::size_t mi = n.hit.tri < scene.mesh.tri_material.size() ? scene.mesh.tri_material[n.hit.tri] : 0;
        const Material m = mi < scene.mesh.materials.size() ? scene.mesh.materials[mi] : Material{};
        const Vec3 above = p + kOffset * ng;
        const Vec3 below = p - kOffset * ng;
        const bool deeper = n.depth < opts.max_depth;

        const std::size_t first = tree.size();
        auto& kids = tree;  // children go straight after the tree's current end
        float base = 0.0f;
        switch (m.kind) {
            case MaterialKind::Diffuse:
                base = opts.ambient;
                for (const Light& l : lights) {
                    const Vec3 to = l.position - p;
                    const float len = glm::length(to);
                    if (len <= 0.0f || glm::dot(ng, to) <= 0.0f) continue;
                    const float lambert = glm::dot(ns, to) / len;
                    if (lambert <= 0.0f) continue;
                    kids.push_back(child(n, RayKind::Shadow, above, l.position - above, 1.0f, lambert * l.color, n.inside));
                }
                break;
            case MaterialKind::Mirror:
                if (!deeper) {
                    base = opts.ambient;
                    break;
                }
                kids.push_back(child(n, RayKind::Reflection, above, reflect_dir(dir, ns, ng), kInf, Vec3(1.0f), n.inside));
                break;
            case MaterialKind::Glass: {
                if (!deeper) {
                    base = opts.ambient;
                    break;
                }
                const float eta = n.inside ? m.ior : 1.0f / m.ior;
                const float cosi = std::min(1.0f, -glm::dot(dir, ns));
                const float k = 1.0f - eta * eta * (1.0f - cosi * cosi);
                const Vec3 refl = reflect_dir(dir, ns, ng);
                if (k < 0.0f) {  // total internal reflection
                    kids.push_back(child(n, RayKind::Reflection, above, refl, kInf, Vec3(1.0f), n.inside));
                    break;
                }
                const float cost = std::sqrt(k);
                Vec3 refr = eta * dir + (eta * cosi - cost) * ns;
                if (glm::dot(refr, ng) >= 0.0f) refr = dir;  // grazing: pass straight on
                const float r0 = ((m.ior - 1.0f) / (m.ior + 1.0f)) * ((m.ior - 1.0f) / (m.ior + 1.0f));
                const float c = 1.0f - (n.inside ? cost : cosi);
                const float fr = r0 + (1.0f - r0) * c * c * c * c * c;
                kids.push_back(child(n, RayKind::Reflection, above, refl, kInf, Vec3(fr), n.inside));
                kids.push_back(child(n, RayKind::Refraction, below, refr, kInf, Vec3(1.0f - fr), !n.inside));
                break;
            }
        }
        RayNode& out = tree[i];
        out.tint = m.color;
        out.base = base;
        out.first_child = static_cast<std::int32_t>(first);
        out.n_children = static_cast<std::uint8_t>(tree.size() - first);
    }

    static Vec3 reflect_dir(const Vec3& d, const Vec3& ns, const Vec3& ng) {
        Vec3 r = d - 2.0f * glm::dot(d, ns) * ns;
        if (glm::dot(r, ng) <= 0.0f) r = d - 2.0f * glm::dot(d, ng) * ng;
        return r;
    }

    Vec3 evaluate(const PixelTree& tree, std::size_t i) const {
        const RayNode& n = tree[i];
        if (!n.hit.found()) return opts.background;
        Vec3 sum(n.base);
        for (int k = 0; k < n.n_children; ++k) {
            const std::size_t c = static_cast<std::size_t>(n.first_child + k);
            const RayNode& ch = tree[c];
            if (ch.kind == RayKind::Shadow) {
                if (!ch.occluded) sum += ch.weight;
            } else {
                sum += ch.weight * evaluate(tree, c);
            }
        }
        return n.tint * sum;
    }

    const RenderScene& scene;
    const RenderOptions& opts;
    Camera cam;
    std::vector<Light> lights;
    Vec3 u, v, w;
    float tan_half = 0.0f, aspect = 1.0f;
};

void check_options(const RenderOptions& o) {
    if (o.width < 1 || o.height < 1) throw InputError("--size: the image needs at least one pixel");
    if (o.max_depth < 0 || o.max_depth > 32) throw InputError("--max-depth: must be in 0..32");
    if (o.threads < 1) throw InputError("--threads: must be at least 1");
    if (o.pool < 1) throw InputError("--pool: must be at least 1");
    if (o.lights.size() > 16) throw InputError("render: at most 16 lights");
    if (o.light_count < 1 || o.light_count > 2) throw InputError("--lights: must be 1 or 2");
    check_combination(o.test, o.order);
}

// The fixed path needs the Accel quantised with the format of the options,
// the local path localised with them.
void check_quantized(const RenderScene& scene, const RenderOptions& o) {
    if (o.test == BoxTestKind::Fixed) {
        const FixedFormat& a = scene.accel.format;
        if (!scene.accel.quantized || a.coord_bits != o.fixed.coord_bits || a.dir_bits != o.fixed.dir_bits ||
            a.mode != o.fixed.mode)
            throw std::logic_error("render: the Accel is not quantised with the options' fixed-point format");
    }
    if (o.test == BoxTestKind::Local) {
        const LocalBvh* l = scene.accel.local.get();
        if (!l || l->format.box_bits != o.local.box_bits || l->format.dir_bits != o.local.dir_bits ||
            l->format.grid_bits != o.local.grid_bits || l->format.mode != o.local.mode || !(l->options == o.local_build))
            throw std::logic_error("render: the Accel is not localised with the options' local format");
    }
}

// Traces the whole tree of one pixel with a tracer, breadth first.
Vec3 render_pixel(const Shader& sh, const Tracer& tr, int x, int y, PixelTree& tree, RenderStats& st) {
    Shader::start(tree, sh.camera_ray(x, y));
    for (std::size_t i = 0; i < tree.size(); ++i) {
        RayNode& n = tree[i];
        ++st.rays[static_cast<int>(n.kind)];
        if (n.kind == RayKind::Shadow)
            n.occluded = tr.occluded(n.ray, st.traversal);
        else
            n.hit = tr.closest(n.ray, st.traversal);
        st.hits[static_cast<int>(n.kind)] += n.kind == RayKind::Shadow ? n.occluded : n.hit.found();
        sh.expand(tree, i);
    }
    return sh.evaluate(tree, 0);
}

class Progress {
public:
    Progress(bool on, std::uint64_t total) : on_(on), total_(total) {}
    void update(std::uint64_t done) {
        if (!on_ || total_ == 0) return;
        const int tenth = static_cast<int>(done * 10 / total_);
        if (tenth > last_) {
            last_ = tenth;
            std::fprintf(stderr, "render: %3d%%\n", tenth * 10);
        }
    }

private:
    bool on_;
    std::uint64_t total_;
    int last_ = 0;
};

double ms_since(std::chrono::steady_clock::time_point t0) {
    return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
}

void add_stats(RenderStats& a, const RenderStats& b) {
    for (int k = 0; k < kRayKinds; ++k) {
        a.rays[k] += b.rays[k];
        a.hits[k] += b.hits[k];
    }
    a.traversal += b.traversal;
}

}  // namespace

// ---------------------------------------------------------------------------
// Set-up

std::unique_ptr<RenderSetup> make_render_setup(const std::string& scene_spec, const BuildOptions& build,
                                               const RenderOptions& opts) {
    check_options(opts);
    if (opts.test == BoxTestKind::Fixed) opts.fixed.validate();
    if (opts.test == BoxTestKind::Local) opts.local.validate();
    auto s = std::make_unique<RenderSetup>();
    s->opts = opts;
    s->build = build.method;
    s->mesh = make_scene(scene_spec);
    s->bvh = build_bvh(s->mesh, build);
    s->accel = std::make_unique<Accel>(s->mesh, s->bvh);
    if (opts.test == BoxTestKind::Fixed) s->accel->quantize(opts.fixed);
    if (opts.test == BoxTestKind::Local) s->accel->localize(opts.local, opts.local_build);
    s->scene = std::make_unique<RenderScene>(s->mesh, *s->accel);
    return s;
}

// ---------------------------------------------------------------------------
// Render paths

namespace {
// A binary32 unit's model through the batched path (as its RTL renders).
template <BoxTestKind T>
Image render_f32(const RenderScene& scene, const RenderOptions& opts, RenderStats& st) {
    SoftwareF32Engine<T> engine;
    return render_batched(scene, opts, engine, st);
}
}  // namespace

Image render(const RenderScene& scene, const RenderOptions& opts, RenderStats& st) {
    if (opts.test == BoxTestKind::Local) {
        SoftwareLocalEngine engine(opts.local);
        return render_batched(scene, opts, engine, st);
    }
    if (opts.test == BoxTestKind::F32Pluecker) return render_f32<BoxTestKind::F32Pluecker>(scene, opts, st);
    if (opts.test == BoxTestKind::F32PlueckerCons) return render_f32<BoxTestKind::F32PlueckerCons>(scene, opts, st);
    if (opts.test == BoxTestKind::F32Smits) return render_f32<BoxTestKind::F32Smits>(scene, opts, st);
    if (opts.test != BoxTestKind::Fixed) return render_direct(scene, opts, st);
    SoftwareBoxEngine engine(opts.fixed);
    return render_batched(scene, opts, engine, st);
}

Image render_direct(const RenderScene& scene, const RenderOptions& opts, RenderStats& st) {
    check_options(opts);
    check_quantized(scene, opts);
    const auto tracer = make_tracer(scene.accel, opts.test, opts.order);
    return render_direct(scene, opts, *tracer, st);
}

Image render_direct(const RenderScene& scene, const RenderOptions& opts, const Tracer& tracer, RenderStats& st) {
    check_options(opts);
    const auto t0 = std::chrono::steady_clock::now();
    const Shader sh(scene, opts);
    Image img(opts.width, opts.height);
    const int nthreads = std::min(opts.threads, opts.height);
    std::vector<RenderStats> part(static_cast<std::size_t>(nthreads));
    std::atomic<int> next_row{0};
    std::atomic<int> rows_done{0};
    Progress progress(opts.progress, static_cast<std::uint64_t>(opts.height));
    auto work = [&](int id) {
        PixelTree tree;
        tree.reserve(64);
        for (;;) {
            const int y = next_row.fetch_add(1);
            if (y >= opts.height) break;
            for (int x = 0; x < opts.width; ++x) img.set(x, y, render_pixel(sh, tracer, x, y, tree, part[id]));
            const int done = rows_done.fetch_add(1) + 1;
            if (id == 0) progress.update(static_cast<std::uint64_t>(done));
        }
    };
    if (nthreads == 1) {
        work(0);
    } else {
        std::vector<std::thread> pool;
        for (int i = 0; i < nthreads; ++i) pool.emplace_back(work, i);
        for (auto& t : pool) t.join();
    }
    for (const auto& p : part) add_stats(st, p);
    st.render_ms += ms_since(t0);
    return img;
}

namespace {

template <class Engine>
Image render_batched_t(const RenderScene& scene, const RenderOptions& opts, Engine& engine, RenderStats& st,
                       BoxTestKind test) {
    check_options(opts);
    if (opts.test != test)
        throw InputError(std::string("render_batched: this engine needs --test ") + test_name(test));
    check_quantized(scene, opts);
    const auto t0 = std::chrono::steady_clock::now();
    const Shader sh(scene, opts);
    Image img(opts.width, opts.height);
    const std::uint64_t npix = static_cast<std::uint64_t>(opts.width) * static_cast<std::uint64_t>(opts.height);
    // Pixels in flight: their ray trees and the count of rays not yet done.
    struct PixelState {
        PixelTree tree;
        std::uint32_t outstanding = 0;
    };
    std::unordered_map<std::uint64_t, PixelState> pixels;
    std::deque<std::uint64_t> ready;  // tag = pixel << 16 | node; served before new pixels
    std::uint64_t next_pixel = 0, pixels_done = 0;
    Progress progress(opts.progress, npix);
    constexpr std::uint64_t kNodeBits = 16;

    auto next = [&](BatchRay& br) {
        std::uint64_t tag;
        if (!ready.empty()) {
            tag = ready.front();
            ready.pop_front();
        } else if (next_pixel < npix) {
            const std::uint64_t p = next_pixel++;
            const int x = static_cast<int>(p % static_cast<std::uint64_t>(opts.width));
            const int y = static_cast<int>(p / static_cast<std::uint64_t>(opts.width));
            PixelState& ps = pixels[p];
            Shader::start(ps.tree, sh.camera_ray(x, y));
            ps.outstanding = 1;
            tag = p << kNodeBits;
        } else {
            return false;
        }
        const RayNode& n = pixels.at(tag >> kNodeBits).tree[tag & ((1u << kNodeBits) - 1)];
        ++st.rays[static_cast<int>(n.kind)];
        br = BatchRay{n.ray, n.kind == RayKind::Shadow, tag};
        return true;
    };
    auto finish = [&](const BatchResult& r) {
        const std::uint64_t p = r.tag >> kNodeBits;
        const std::size_t i = static_cast<std::size_t>(r.tag & ((1u << kNodeBits) - 1));
        PixelState& ps = pixels.at(p);
        PixelTree& tree = ps.tree;
        if (tree[i].kind == RayKind::Shadow)
            tree[i].occluded = r.hit.found();
        else
            tree[i].hit = r.hit;
        st.hits[static_cast<int>(tree[i].kind)] += r.hit.found();
        const std::size_t before = tree.size();
        sh.expand(tree, i);
        if (tree.size() >= (std::size_t{1} << kNodeBits)) throw std::logic_error("render: ray tree too large");
        for (std::size_t c = before; c < tree.size(); ++c) ready.push_back(p << kNodeBits | c);
        ps.outstanding += static_cast<std::uint32_t>(tree.size() - before);
        if (--ps.outstanding == 0) {
            const int x = static_cast<int>(p % static_cast<std::uint64_t>(opts.width));
            const int y = static_cast<int>(p / static_cast<std::uint64_t>(opts.width));
            img.set(x, y, sh.evaluate(tree, 0));
            pixels.erase(p);
            progress.update(++pixels_done);
        }
    };
    run_batched(scene.accel, opts.order, engine, opts.pool, next, finish, st.traversal, &st.batch);
    st.render_ms += ms_since(t0);
    return img;
}

}  // namespace

Image render_batched(const RenderScene& scene, const RenderOptions& opts, BoxEngine& engine, RenderStats& st) {
    return render_batched_t(scene, opts, engine, st, BoxTestKind::Fixed);
}
Image render_batched(const RenderScene& scene, const RenderOptions& opts, LocalBoxEngine& engine, RenderStats& st) {
    return render_batched_t(scene, opts, engine, st, BoxTestKind::Local);
}
template <BoxTestKind T>
Image render_batched(const RenderScene& scene, const RenderOptions& opts, F32BoxEngine<T>& engine, RenderStats& st) {
    return render_batched_t(scene, opts, engine, st, T);
}
template Image render_batched<BoxTestKind::F32Pluecker>(const RenderScene&, const RenderOptions&,
                                                        F32BoxEngine<BoxTestKind::F32Pluecker>&, RenderStats&);
template Image render_batched<BoxTestKind::F32PlueckerCons>(const RenderScene&, const RenderOptions&,
                                                            F32BoxEngine<BoxTestKind::F32PlueckerCons>&, RenderStats&);
template Image render_batched<BoxTestKind::F32Smits>(const RenderScene&, const RenderOptions&,
                                                     F32BoxEngine<BoxTestKind::F32Smits>&, RenderStats&);

std::uint64_t trace_render(const RenderScene& scene, const RenderOptions& opts, std::ostream& out, std::uint64_t limit,
                           RenderStats& st) {
    check_options(opts);
    check_quantized(scene, opts);
    const auto t0 = std::chrono::steady_clock::now();
    const Shader sh(scene, opts);
    std::vector<Query> record;
    const auto tracer = make_tracer(scene.accel, opts.test, opts.order, &record);
    PixelTree tree;
    std::uint64_t written = 0;
    Progress progress(opts.progress, static_cast<std::uint64_t>(opts.height));
    for (int y = 0; y < opts.height; ++y) {
        for (int x = 0; x < opts.width; ++x) {
            record.clear();
            render_pixel(sh, *tracer, x, y, tree, st);
            for (const Query& q : record) {
                if (limit != 0 && written == limit) break;
                write_query(out, q);
                ++written;
            }
            if (limit != 0 && written == limit) {
                st.render_ms += ms_since(t0);
                return written;
            }
        }
        progress.update(static_cast<std::uint64_t>(y + 1));
    }
    st.render_ms += ms_since(t0);
    return written;
}

// ---------------------------------------------------------------------------
// Statistics

nlohmann::json stats_json(const RenderScene& scene, const Bvh& bvh, BuildMethod build, const RenderOptions& opts,
                          const RenderStats& st) {
    nlohmann::json j;
    j["scene"] = scene.mesh.name;
    j["triangles"] = scene.mesh.triangles.size();
    j["test"] = test_name(opts.test);
    j["order"] = order_name(opts.order);
    j["config"] = config_name(opts.test, opts.order);
    j["build"] = method_name(build);
    j["width"] = opts.width;
    j["height"] = opts.height;
    j["max_depth"] = opts.max_depth;
    nlohmann::json rays;
    std::uint64_t total = 0;
    for (int k = 0; k < kRayKinds; ++k) {
        rays[ray_kind_name(static_cast<RayKind>(k))] = st.rays[k];
        total += st.rays[k];
    }
    rays["total"] = total;
    j["rays"] = rays;
    nlohmann::json hits;
    total = 0;
    for (int k = 0; k < kRayKinds; ++k) {
        hits[ray_kind_name(static_cast<RayKind>(k))] = st.hits[k];
        total += st.hits[k];
    }
    hits["total"] = total;
    j["hits"] = hits;
    j["node_visits"] = st.traversal.node_visits;
    j["box_tests"] = st.traversal.box_tests;
    j["triangle_tests"] = st.traversal.tri_tests;
    j["build_ms"] = bvh.build_ms;
    j["render_ms"] = st.render_ms;
    j["bvh"] = {{"nodes", bvh.nodes.size()}, {"leaves", bvh.leaf_count()}, {"depth", bvh.depth()}};
    if (is_batched(opts.test)) {
        if (is_f32_unit(opts.test))
            j["f32"] = {{"unit", test_name(opts.test)}};
        else if (opts.test == BoxTestKind::Fixed)
            j["fixed"] = {{"coord_bits", opts.fixed.coord_bits},
                          {"dir_bits", opts.fixed.dir_bits},
                          {"mode", mode_name(opts.fixed.mode)}};
        else
            j["local"] = {{"box_bits", opts.local.box_bits},
                          {"dir_bits", opts.local.dir_bits},
                          {"grid_bits", opts.local.grid_bits},
                          {"mode", mode_name(opts.local.mode)},
                          {"uniform", opts.local_build.uniform},
                          {"parent_origin", opts.local_build.parent_origin},
                          {"node_bits", scene.accel.local->memory_bits()},
                          {"float_node_bits", LocalBvh::kFloatNodeBits}};
        j["batch"] = {{"pool", opts.pool},
                      {"batches", st.batch.batches},
                      {"queries", st.batch.queries},
                      {"max_batch", st.batch.max_batch}};
        j["threads"] = 1;
    } else {
        j["threads"] = opts.threads;
    }
    return j;
}

}  // namespace pluecker
