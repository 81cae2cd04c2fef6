// SPDX-License-Identifier: MIT
#include "pluecker/app/render_options.hpp"

#include "pluecker/app/names.hpp"

#include "pluecker/bvh.hpp"
#include "pluecker/mesh.hpp"
#include "pluecker/traversal.hpp"

#include <glm/geometric.hpp>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <limits>
#include <sstream>

namespace pluecker::app {

const std::set<std::string> kSceneOptions = {
    "scene", "test",  "order", "build", "size", "width", "height",    "coord-bits", "dir-bits", "mode",
    "epsilon", "eye", "look",  "up",    "fov",  "max-depth", "lights", "out",      "threads",  "pool",
    "box-bits", "grid-bits", "frames", "cells"};

const char* const kSceneHelp =
    "  --scene S        teapot | spheres | sphere:N | FILE (mesh formats below) [teapot]\n"
    "  --test T         exact | smits | pluecker | fixed | local         [pluecker]\n"
    "                   | f32-pluecker | f32-pluecker-cons | f32-smits (the binary32\n"
    "                   units' bit-exact models, f32unit.hpp, on the float BVH)\n"
    "  --order O        fixed | dsa | dist (dist: smits only)            [dsa]\n"
    "  --build B        median | sah                                     [sah]\n"
    "  --size N         image N x N                                      [512]\n"
    "  --width W --height H   override the size per axis\n"
    "  --coord-bits N --dir-bits M --mode conservative|nearest   fixed test only [16 16 conservative]\n"
    "  --box-bits K --dir-bits D --grid-bits G --mode M   local test (local frames) [8, K+3, 32, conservative]\n"
    "  --frames parent|own   local: frame origins from the parent's grid or stored per node [parent]\n"
    "  --cells axis|uniform  local: a power-of-two cell per axis or one for all three [axis]\n"
    "  --epsilon E      BVH box growth                                   [1e-6]\n"
    "  --eye X,Y,Z --look X,Y,Z --up X,Y,Z --fov DEG   camera (default: per scene)\n"
    "  --lights N       1 or 2 point lights                              [2]\n"
    "  --max-depth D    reflection/refraction levels                     [4]\n";

std::string mesh_formats_help() {
    std::string out = "mesh files (read with Assimp, chosen by extension, case-insensitive):\n";
    for (const MeshFormat& f : mesh_formats()) {
        std::string exts;
        for (const std::string& e : f.extensions) exts += (exts.empty() ? "" : " ") + e;
        out += "  " + exts + std::string(exts.size() < 24 ? 24 - exts.size() : 1, ' ') + f.name + "\n";
    }
    return out;
}

Vec3 parse_vec3(const Args& a, const std::string& name, const Vec3& fallback) {
    if (!a.has(name)) return fallback;
    const std::string s = a.get(name, "");
    Vec3 v;
    std::size_t pos = 0;
    for (int k = 0; k < 3; ++k) {
        const std::size_t comma = s.find(',', pos);
        if ((k < 2) != (comma != std::string::npos))
            throw InputError("option --" + name + ": '" + s + "' is not three numbers X,Y,Z");
        const std::string part = s.substr(pos, k < 2 ? comma - pos : std::string::npos);
        char* end = nullptr;
        const double x = std::strtod(part.c_str(), &end);
        if (part.empty() || *end != '\0' || !std::isfinite(x))
            throw InputError("option --" + name + ": '" + part + "' is not a finite number");
        if (std::fabs(x) > std::numeric_limits<float>::max())  // a float cast of it is undefined
            throw InputError("option --" + name + ": '" + part + "' is outside the float range");
        v[k] = static_cast<float>(x);
        pos = comma + 1;
    }
    return v;
}

float parse_epsilon(const Args& a, float fallback) {
    if (!a.has("epsilon")) return fallback;
    const double e = a.get_double("epsilon", fallback);
    const std::string s = a.get("epsilon", "");
    if (!std::isfinite(e)) throw InputError("option --epsilon: '" + s + "' is not a finite number");
    if (!(e >= 0.0)) throw InputError("option --epsilon: must be >= 0 (got " + s + ")");
    if (e > std::numeric_limits<float>::max()) throw InputError("option --epsilon: '" + s + "' is outside the float range");
    return static_cast<float>(e);
}

void check_epsilon_fixed(float epsilon, const FixedFormat& f) {
    const Box widest{Vec3(-1.0f - epsilon), Vec3(1.0f + epsilon)};
    try {
        (void)fixed_quantize_box(widest, f);
    } catch (const InputError&) {
        std::ostringstream os;
        os << "option --epsilon: " << epsilon << " grows the BVH boxes of the scene (normalised to [-1, 1]) to ["
           << widest.lo.x << ", " << widest.hi.x << "], outside the fixed-point range " << f.range_text()
           << " of --test fixed";
        throw InputError(os.str());
    }
}

void check_epsilon_local(float epsilon, const LocalFormat& f) {
    const Box widest{Vec3(-1.0f - epsilon), Vec3(1.0f + epsilon)};
    try {
        (void)local_frame_for(widest, f);
    } catch (const InputError&) {
        std::ostringstream os;
        os << "option --epsilon: " << epsilon << " grows the BVH boxes of the scene (normalised to [-1, 1]) to ["
           << widest.lo.x << ", " << widest.hi.x << "], outside the range " << f.range_text() << " of --test local";
        throw InputError(os.str());
    }
}

LocalFormat parse_local_format(const Args& a, FixedMode mode) {
    LocalFormat f;
    f.box_bits = static_cast<int>(
        a.get_int("box-bits", f.box_bits, LocalFormat::kMinBoxBits, LocalFormat::kMaxBoxBits));
    f.dir_bits = static_cast<int>(a.get_int("dir-bits", std::min(f.box_bits + 3, LocalFormat::kMaxDirBits),
                                            LocalFormat::kMinDirBits, LocalFormat::kMaxDirBits));
    f.grid_bits = static_cast<int>(a.get_int("grid-bits", f.grid_bits, f.box_bits + 2, LocalFormat::kMaxGridBits));
    f.mode = mode;
    return f;
}

LocalBuildOptions parse_local_build(const Args& a) {
    LocalBuildOptions o;
    const std::string frames = a.get("frames", "parent"), cells = a.get("cells", "axis");
    if (frames != "parent" && frames != "own")
        throw InputError("option --frames: '" + frames + "' is not one of parent, own");
    if (cells != "axis" && cells != "uniform")
        throw InputError("option --cells: '" + cells + "' is not one of axis, uniform");
    o.parent_origin = frames == "parent";
    o.uniform = cells == "uniform";
    return o;
}

void check_camera(const Camera& c) {
    auto finite = [](const Vec3& x) { return std::isfinite(x.x) && std::isfinite(x.y) && std::isfinite(x.z); };
    auto nonzero = [](const Vec3& x) { return x.x != 0.0f || x.y != 0.0f || x.z != 0.0f; };
    const Vec3 diff = c.eye - c.look;
    if (!nonzero(diff)) throw InputError("options --eye and --look: must differ");
    const auto [w, side, u, v] = camera_basis(c);  // the renderer's own frame
    if (!finite(diff) || !finite(w) || !nonzero(w))
        throw InputError("options --eye and --look: the view direction eye - look cannot be normalised in "
                         "float arithmetic (its length must lie between about 1e-18 and 1e18)");
    if (finite(side) && !nonzero(side)) throw InputError("option --up: parallel to the view direction");
    if (!finite(side) || !finite(u) || !nonzero(u))
        throw InputError("option --up: cross(up, view direction) cannot be normalised in float arithmetic "
                         "(|up| must lie between about 1e-18 and 1e18, and up must not be nearly parallel to "
                         "the view direction)");
    if (!finite(v) || !nonzero(v)) throw InputError("options --eye, --look and --up: no valid camera basis");
}

std::unique_ptr<SceneSetup> make_setup(const Args& a) {
    RenderOptions o;
    o.test = parse_box_test(a.get("test", "pluecker"));
    o.order = parse_child_order(a.get("order", "dsa"));
    check_combination(o.test, o.order);
    BuildOptions bo;
    bo.method = with_flag("build", [&] { return parse_build_method(a.get("build", "sah")); });
    const long size = a.get_int("size", 512, 1, 16384);
    o.width = static_cast<int>(a.get_int("width", size, 1, 16384));
    o.height = static_cast<int>(a.get_int("height", size, 1, 16384));
    const bool fixed = o.test == BoxTestKind::Fixed;
    const bool local = o.test == BoxTestKind::Local;
    if (a.has("coord-bits") && !fixed) throw InputError("option --coord-bits needs --test fixed");
    for (const char* f : {"dir-bits", "mode"})
        if (a.has(f) && !fixed && !local) throw InputError(std::string("option --") + f + " needs --test fixed or local");
    if (a.has("pool") && !is_batched(o.test))
        throw InputError("option --pool needs a batched test (fixed, local, f32-pluecker, f32-pluecker-cons, f32-smits)");
    for (const char* f : {"box-bits", "grid-bits", "frames", "cells"})
        if (a.has(f) && !local) throw InputError(std::string("option --") + f + " needs --test local");
    const FixedMode mode = with_flag("mode", [&] { return parse_fixed_mode(a.get("mode", "conservative")); });
    if (local) {
        o.local = parse_local_format(a, mode);
        o.local_build = parse_local_build(a);
    } else {
        o.fixed.coord_bits = static_cast<int>(a.get_int("coord-bits", FixedFormat::kDefaultCoordBits,
                                                        FixedFormat::kMinBits, FixedFormat::kMaxBits));
        o.fixed.dir_bits = static_cast<int>(
            a.get_int("dir-bits", FixedFormat::kDefaultDirBits, FixedFormat::kMinBits, FixedFormat::kMaxBits));
        o.fixed.mode = mode;
    }
    o.threads = static_cast<int>(a.get_int("threads", 1, 1, 1024));
    o.pool = static_cast<std::size_t>(a.get_int("pool", 256, 1, 1 << 20));
    o.max_depth = static_cast<int>(a.get_int("max-depth", 4, 0, 32));
    o.light_count = static_cast<int>(a.get_int("lights", 2, 1, 2));
    bo.epsilon = parse_epsilon(a, bo.epsilon);
    if (fixed) check_epsilon_fixed(bo.epsilon, o.fixed);
    if (local) check_epsilon_local(bo.epsilon, o.local);

    // Camera flags are checked before the (possibly long) build; the
    // defaults they override come from the scene.
    const bool camera = a.has("eye") || a.has("look") || a.has("up") || a.has("fov");
    const Vec3 nan3(std::nanf(""));
    const Vec3 eye = parse_vec3(a, "eye", nan3), look = parse_vec3(a, "look", nan3), up = parse_vec3(a, "up", nan3);
    const float fov = static_cast<float>(a.get_double("fov", 40.0));
    if (!(fov > 0.0f && fov < 180.0f)) throw InputError("option --fov: must be in (0, 180)");

    auto s = make_render_setup(a.get("scene", "teapot"), bo, o);
    if (camera) {
        Camera c = default_camera(s->mesh);
        if (a.has("eye")) c.eye = eye;
        if (a.has("look")) c.look = look;
        if (a.has("up")) c.up = up;
        if (a.has("fov")) c.fov_deg = fov;
        check_camera(c);
        s->opts.camera = c;
    }
    return s;
}

}  // namespace pluecker::app
