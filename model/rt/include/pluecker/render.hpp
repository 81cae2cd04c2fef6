// SPDX-License-Identifier: MIT
// A small Whitted-style ray tracer over the traversal of traverse.hpp.
//
// Camera     pinhole, one ray through each pixel centre. The default view
//            looks at the centre of the scene's bounds from a per-scene
//            direction, at the distance where the sphere around the centre
//            through the farthest vertex just fits the vertical field of view.
// Lights     one or two point lights placed relative to the camera, outside
//            the scene cube.
// Shading    Diffuse: Lambert (interpolated vertex normals) plus an ambient
//            term; each light is tested with a shadow ray, an any-hit
//            segment from the surface to the light (tmax = 1 over the
//            unnormalised direction). Mirror: the material colour times the
//            reflected ray. Glass: reflection and refraction weighted by
//            Schlick's approximation of the Fresnel factor (Schlick,
//            Computer Graphics Forum 13(3), 1994), total internal reflection
//            when Snell's law has no solution; whether a ray is inside glass
//            is tracked along the ray tree, so mesh winding does not matter.
//            Reflection and refraction rays stop at max_depth; a ray that
//            misses returns the background colour. Secondary rays start
//            1e-4 off the surface along the geometric normal.
//
// Determinism
//   Each pixel is a tree of rays: a ray's children (shadow rays in light
//   order, then reflection, then refraction) are made from its hit alone,
//   and the pixel's colour is evaluated from the finished tree in that fixed
//   order. The image therefore does not depend on the order in which rays
//   are traced: threads, batch size and pool size change nothing.
#pragma once

#include "pluecker/bvh.hpp"
#include "pluecker/image.hpp"
#include "pluecker/mesh.hpp"
#include "pluecker/accel.hpp"
#include "pluecker/batched.hpp"
#include "pluecker/traversal.hpp"

#include <nlohmann/json.hpp>

#include <array>
#include <cstdint>
#include <iosfwd>
#include <memory>
#include <optional>
#include <string>
#include <vector>

namespace pluecker {

struct Camera {
    Vec3 eye{0.0f, 0.0f, 3.0f};
    Vec3 look{0.0f};
    Vec3 up{0.0f, 1.0f, 0.0f};
    float fov_deg = 40.0f;  // vertical field of view
};

// The camera's frame: w points from the look-at point to the eye, u to the
// right, v up. `side` is cross(up, w) before normalising (zero when up is
// parallel to the view). Degenerate cameras give NaN or zero vectors; the
// applications reject them before rendering (render_options.hpp).
struct CameraBasis {
    Vec3 w, side, u, v;
};
CameraBasis camera_basis(const Camera& c);

struct Light {
    Vec3 position;
    Vec3 color;
};

enum class RayKind : std::uint8_t { Camera, Shadow, Reflection, Refraction };
inline constexpr int kRayKinds = 4;
const char* ray_kind_name(RayKind k);

struct RenderOptions {
    int width = 512;
    int height = 512;
    BoxTestKind test = BoxTestKind::Pluecker;
    ChildOrder order = ChildOrder::Dsa;
    FixedFormat fixed;                 // used by the fixed test
    LocalFormat local;                 // used by the local test
    LocalBuildOptions local_build;     // its hierarchy
    std::optional<Camera> camera;      // default_camera() when empty
    std::vector<Light> lights;         // default_lights() when empty
    int light_count = 2;               // for default_lights(): 1 or 2
    Vec3 background{0.05f, 0.06f, 0.08f};
    float ambient = 0.08f;
    int max_depth = 4;                 // reflection/refraction levels
    int threads = 1;                   // float tests: worker threads over rows
    std::size_t pool = 256;            // fixed test: rays in flight
    bool progress = false;             // progress lines on stderr
};

struct RenderStats {
    std::array<std::uint64_t, kRayKinds> rays{};  // by RayKind
    std::array<std::uint64_t, kRayKinds> hits{};  // rays that hit (shadow: occluded), by RayKind
    TraversalStats traversal;
    BatchStats batch;  // the batched path only
    double render_ms = 0;
};

Camera default_camera(const Mesh& m);
std::vector<Light> default_lights(const Camera& c, int count);

// The scene's render-ready data: the mesh, its traversal structure and
// smooth vertex normals. The mesh and accel must outlive it.
struct RenderScene {
    RenderScene(const Mesh& m, const Accel& a);
    const Mesh& mesh;
    const Accel& accel;
    std::vector<Vec3> normals;  // area-weighted, one per vertex
};

// Everything a render needs, built in one call (the CLI and the
// hardware-in-the-loop harness both start here): the scene from its spec
// (make_scene), the BVH, the Accel (quantised with opts.fixed when opts.test
// is fixed, localised with opts.local when it is local) and the shading
// data. Checks the options (InputError).
struct RenderSetup {
    Mesh mesh;
    Bvh bvh;
    BuildMethod build = BuildMethod::Sah;
    std::unique_ptr<Accel> accel;
    std::unique_ptr<RenderScene> scene;
    RenderOptions opts;
};
std::unique_ptr<RenderSetup> make_render_setup(const std::string& scene_spec, const BuildOptions& build,
                                               const RenderOptions& opts);

// Renders with opts.test: the fixed, local and binary32-unit tests go
// through render_batched with a software engine, the float tests through
// render_direct. The fixed test needs scene.accel quantised with opts.fixed,
// the local test localised with opts.local (std::logic_error otherwise).
Image render(const RenderScene& scene, const RenderOptions& opts, RenderStats& st);

// Every ray traced at once by the Tracer of opts.test/opts.order, pixels
// spread over opts.threads threads (any test, the fixed one included).
Image render_direct(const RenderScene& scene, const RenderOptions& opts, RenderStats& st);
// The same render with a caller's tracer in place of the one made from
// scene.accel and opts.test/opts.order (e.g. a K-D tree's, kdtree.hpp): same
// camera, lights, ray trees and shading; opts.test/opts.order only label the
// render. The tracer is called from opts.threads threads at once.
Image render_direct(const RenderScene& scene, const RenderOptions& opts, const Tracer& tracer, RenderStats& st);

// The hardware-in-the-loop path: rays of all pixels go through run_batched
// with opts.pool rays in flight; every box test is answered by `engine`.
// opts.test must be fixed (BoxEngine), local (LocalBoxEngine) or the
// binary32 unit T (F32BoxEngine<T>), opts.order fixed or dsa.
Image render_batched(const RenderScene& scene, const RenderOptions& opts, BoxEngine& engine, RenderStats& st);
Image render_batched(const RenderScene& scene, const RenderOptions& opts, LocalBoxEngine& engine, RenderStats& st);
template <BoxTestKind T>
Image render_batched(const RenderScene& scene, const RenderOptions& opts, F32BoxEngine<T>& engine, RenderStats& st);

// The binary32 units' models (f32-pluecker, f32-pluecker-cons, f32-smits).
inline bool is_f32_unit(BoxTestKind t) {
    return t == BoxTestKind::F32Pluecker || t == BoxTestKind::F32PlueckerCons || t == BoxTestKind::F32Smits;
}
// The batched tests: those with a datapath model (fixed, local, the binary32
// units).
inline bool is_batched(BoxTestKind t) { return t == BoxTestKind::Fixed || t == BoxTestKind::Local || is_f32_unit(t); }

// Writes (write_query) the box queries of the render's traversal in the
// order it issues them: single thread, pixels in row order, each pixel's
// rays breadth first; for the fixed test the clipped ray the box test sees.
// Stops after `limit` queries (0 = no limit). Returns the count written.
std::uint64_t trace_render(const RenderScene& scene, const RenderOptions& opts, std::ostream& out,
                           std::uint64_t limit, RenderStats& st);

// The statistics file of `pluecker render`.
nlohmann::json stats_json(const RenderScene& scene, const Bvh& bvh, BuildMethod build, const RenderOptions& opts,
                          const RenderStats& st);
inline nlohmann::json stats_json(const RenderSetup& s, const RenderStats& st) {
    return stats_json(*s.scene, s.bvh, s.build, s.opts, st);
}

}  // namespace pluecker
