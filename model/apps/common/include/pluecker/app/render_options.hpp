// SPDX-License-Identifier: MIT
// Options shared by `pluecker render`, `pluecker trace`, `pluecker study`,
// `pluecker plan` and `pluecker_sim render`: the scene, the BVH build, the
// box test and child order, the fixed-point format, the image size and the
// camera, turned into a RenderSetup (render.hpp).
#pragma once

#include "pluecker/app/args.hpp"

#include "pluecker/fixed.hpp"
#include "pluecker/local.hpp"
#include "pluecker/render.hpp"

#include <memory>
#include <set>
#include <string>

namespace pluecker::app {

// The flags make_setup reads, and their help lines.
extern const std::set<std::string> kSceneOptions;
extern const char* const kSceneHelp;

// The mesh file formats (--scene FILE), one line each, from the mesh
// library: extensions and name.
std::string mesh_formats_help();

// --NAME as X,Y,Z (finite floats), else `fallback`.
Vec3 parse_vec3(const Args& a, const std::string& name, const Vec3& fallback);

// "option --NAME: " in front of an InputError of a parse_* function whose
// message names the value but not the flag.
template <class F>
auto with_flag(const char* name, F&& parse) {
    try {
        return parse();
    } catch (const InputError& e) {
        throw InputError(std::string("option --") + name + ": " + e.what());
    }
}

// --epsilon: finite, >= 0, and representable as a float (the build works in
// float; a cast of a larger double is undefined).
float parse_epsilon(const Args& a, float fallback);

// With --test fixed every BVH box must quantise into the fixed-point range.
// The scene fills [-1, 1]^3 (make_scene normalises it) and a node box is its
// triangles' bounds grown by epsilon in float, so the largest possible box
// is [-1 - e, 1 + e] on every axis; quantising that one box is the exact
// test, done before the (possibly long) build.
void check_epsilon_fixed(float epsilon, const FixedFormat& f);

// The same for --test local: the widest box must fit the local format's range.
void check_epsilon_local(float epsilon, const LocalFormat& f);

// --box-bits, --dir-bits (default K + 3), --grid-bits of --test local, and
// --frames parent|own, --cells axis|uniform.
LocalFormat parse_local_format(const Args& a, FixedMode mode);
LocalBuildOptions parse_local_build(const Args& a);

// The camera frame the renderer uses (camera_basis): w = normalize(eye -
// look), u = normalize(cross(up, w)), v = cross(w, u). Every one must be
// finite and non-zero, else the rays are NaN; each failure names the flags
// that cause it.
void check_camera(const Camera& c);

// The scene, BVH, Accel and options (pluecker/render.hpp's RenderSetup).
using SceneSetup = RenderSetup;

// Everything a render or a trace needs, built from the flags.
std::unique_ptr<SceneSetup> make_setup(const Args& a);

}  // namespace pluecker::app
