// SPDX-License-Identifier: MIT
// Shared by pluecker_tables and the Embree peer (apps/peer/): the scene
// list, the synthetic scene, the rays of a render (recorded through a
// Tracer wrapper) and random rays.
#pragma once

#include "pluecker/mesh.hpp"
#include "pluecker/render.hpp"
#include "pluecker/rng.hpp"
#include "pluecker/traverse.hpp"

#include "pluecker/app/args.hpp"

#include <glm/geometric.hpp>

#include <algorithm>
#include <cstdint>
#include <filesystem>
#include <memory>
#include <mutex>
#include <set>
#include <string>
#include <utility>
#include <vector>

namespace pluecker::tables {

// The synthetic scene: a field of UV spheres (make_uv_sphere, 4,000
// triangles each) with seeded random radii in [0.02, 0.08] and centres in
// the cube, as many as make about `triangles` triangles; normalised into
// [-1,1]^3 and named "synthetic".
inline Mesh make_synthetic(std::size_t triangles) {
    constexpr std::size_t kPerSphere = 4000;
    const Mesh unit = make_uv_sphere(kPerSphere);
    const std::size_t count = std::max<std::size_t>(1, triangles / unit.triangles.size());
    Mesh m;
    m.name = "synthetic";
    m.materials.push_back(Material{MaterialKind::Diffuse, Vec3(0.75f, 0.7f, 0.6f), 1.5f});
    m.vertices.reserve(count * unit.vertices.size());
    m.triangles.reserve(count * unit.triangles.size());
    Rng rng(2005);
    for (std::size_t i = 0; i < count; ++i) {
        const float r = 0.02f + 0.06f * rng.unit();
        Vec3 c;
        for (int k = 0; k < 3; ++k) c[k] = (2.0f * rng.unit() - 1.0f) * (1.0f - r);
        const auto base = static_cast<std::uint32_t>(m.vertices.size());
        for (const Vec3& v : unit.vertices) m.vertices.push_back(c + r * v);
        for (const auto& t : unit.triangles) m.triangles.push_back({t[0] + base, t[1] + base, t[2] + base});
    }
    m.tri_material.assign(m.triangles.size(), 0);
    normalize_to_cube(m);
    return m;
}

struct SceneSpec {
    std::string label;  // as printed
    std::string spec;   // make_scene spec, or "synthetic:N"
};

// teapot, spheres, the shared scenes present in `shared_dir`, synthetic:N
// (N = 0: none).
inline std::vector<SceneSpec> default_scenes(const std::string& shared_dir, std::size_t synthetic) {
    std::vector<SceneSpec> s{{"teapot", "teapot"}, {"spheres", "spheres"}};
    for (const char* f : {"teapot.obj", "bunny.ply", "dragon_res2.ply"}) {
        const std::filesystem::path p = std::filesystem::path(shared_dir) / f;
        if (std::filesystem::exists(p)) s.push_back({f, p.string()});
    }
    if (synthetic > 0) s.push_back({"synthetic", "synthetic:" + std::to_string(synthetic)});
    return s;
}

// The options pluecker_tables and pluecker_peer share; each tool sets its
// own size, repeat and out defaults.
struct RunOptions {
    RunOptions(int size_, int repeat_, std::string out_) : size(size_), repeat(repeat_), out(std::move(out_)) {}
    int size;                 // --size N: renders N x N
    int repeat;               // --repeat N: best of N timings
    std::string out;          // --out DIR
    std::size_t synthetic = 4000000;          // --synthetic N (0: none)
    std::string shared = "../shared/scenes";  // --shared DIR
    std::vector<std::string> scenes;          // --scenes LIST; empty: default_scenes()
};

// The flags of RunOptions, and reading them (the tool's own defaults stay
// for those not given).
inline const std::set<std::string> kRunOptions = {"size", "repeat", "synthetic", "shared", "out", "scenes"};
inline void read_run_options(const app::Args& args, RunOptions& o) {
    o.size = static_cast<int>(args.get_int("size", o.size, 1, 8192));
    o.repeat = static_cast<int>(args.get_int("repeat", o.repeat, 1, 100));
    o.synthetic = static_cast<std::size_t>(args.get_int("synthetic", static_cast<long>(o.synthetic), 0, 100000000));
    o.shared = args.get("shared", o.shared);
    o.out = args.get("out", o.out);
    o.scenes = args.get_list("scenes", o.scenes);
}

// The scenes to run: those of --scenes, labelled by file name ("synthetic"
// for synthetic:N), else default_scenes.
inline std::vector<SceneSpec> run_scenes(const RunOptions& o) {
    if (o.scenes.empty()) return default_scenes(o.shared, o.synthetic);
    std::vector<SceneSpec> specs;
    for (const std::string& s : o.scenes)
        specs.push_back({s.rfind("synthetic:", 0) == 0 ? "synthetic" : std::filesystem::path(s).filename().string(), s});
    return specs;
}

inline Mesh load_scene(const SceneSpec& s) {
    if (s.spec.rfind("synthetic:", 0) == 0) return make_synthetic(std::stoull(s.spec.substr(10)));
    return make_scene(s.spec);
}

// One traced ray of a render: the ray and whether it is a shadow (any hit) ray.
struct RecordedRay {
    Ray ray;
    bool shadow = false;
};

// Forwards to another tracer and appends every ray to a list (thread-safe).
class RecordingTracer final : public Tracer {
public:
    RecordingTracer(const Tracer& inner, std::vector<RecordedRay>& out) : inner_(inner), out_(out) {}
    Hit closest(const Ray& r, TraversalStats& st) const override {
        add(r, false);
        return inner_.closest(r, st);
    }
    bool occluded(const Ray& r, TraversalStats& st) const override {
        add(r, true);
        return inner_.occluded(r, st);
    }

private:
    void add(const Ray& r, bool shadow) const {
        const std::lock_guard<std::mutex> lock(mutex_);
        out_.push_back(RecordedRay{r, shadow});
    }
    const Tracer& inner_;
    std::vector<RecordedRay>& out_;
    mutable std::mutex mutex_;
};

// Random rays: origins uniform in [-1,1]^3, directions uniform in the unit
// ball (rejection) normalised, unbounded.
inline std::vector<Ray> random_rays(std::size_t n, std::uint64_t seed) {
    Rng rng(seed);
    std::vector<Ray> rays(n);
    for (Ray& r : rays) {
        for (int k = 0; k < 3; ++k) r.o[k] = 2.0f * rng.unit() - 1.0f;
        Vec3 d;
        do {
            for (int k = 0; k < 3; ++k) d[k] = 2.0f * rng.unit() - 1.0f;
        } while (glm::length(d) < 0.05f || glm::length(d) > 1.0f);
        r.d = glm::normalize(d);
        r.tmax = kInf;
    }
    return rays;
}

}  // namespace pluecker::tables
