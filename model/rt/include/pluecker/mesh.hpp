// SPDX-License-Identifier: MIT
// Triangle meshes: the built-in scenes (teapot, spheres, UV sphere) and
// mesh files of every format Assimp reads (mesh_formats()). Every scene that reaches a BVH or a
// renderer goes through make_scene(), which normalises it into [-1,1]^3,
// the coordinate range of the fixed-point format (see fixed.hpp).
//
// Triangle ids are positions in Mesh::triangles; they are stable for a given
// input (same file or same spec gives the same order).
#pragma once

#include "pluecker/geometry.hpp"

#include <array>
#include <cstddef>
#include <cstdint>
#include <functional>
#include <string>
#include <vector>

namespace pluecker {

enum class MaterialKind : std::uint8_t { Diffuse, Mirror, Glass };

struct Material {
    MaterialKind kind = MaterialKind::Diffuse;
    Vec3 color{0.8f};
    float ior = 1.5f;  // index of refraction, used by Glass
};

struct Mesh {
    std::string name;
    std::vector<Vec3> vertices;
    std::vector<std::array<std::uint32_t, 3>> triangles;
    std::vector<std::uint16_t> tri_material;  // one per triangle, index into materials
    std::vector<Material> materials;          // at least one

    // Bounds of all vertices (empty box when there are none).
    Box bounds() const;
};

// Loads a mesh file with Assimp, in any format Assimp reads (chosen by
// extension, case-insensitive: OBJ, PLY, STL ascii and binary, OFF, glTF 2.0
// and GLB, FBX, 3DS, Collada, X3D, 3MF, ... as mesh_formats() lists),
// triangulating polygons (an n-gon gives n-2 consecutive triangles) and
// welding identical vertices within each Assimp mesh (unreferenced vertices
// are dropped). All meshes of the file (OBJ: one per object/group and
// material) are merged in Assimp's mesh order, each placed by the node
// transformations above it (a mesh placed by several nodes appears once per
// placement, in depth-first node order; a mesh in no node stays where it
// is); within a mesh, triangles keep the file's face order. Degenerate and
// duplicate triangles are kept (Assimp's FindDegenerates step is not run);
// point and line primitives are skipped. A PLY file's header and body
// layout are checked before Assimp reads it (Assimp 5.2 hangs on a missing
// end_header or on a vertex or face element without properties, and reads
// garbage from a truncated body): the header lines must be exact ('element
// NAME COUNT' with a whole COUNT below 2^32, 'property TYPE NAME',
// 'property list TYPE TYPE NAME', nothing after), and an element with items
// must have properties; a header line that starts with no keyword (Blender
// 2.47 writes 'Created by Blender3D 247 ...') is taken as a comment with a
// warning, unless its first word is a misspelt keyword. Throws InputError
// naming the file for: a missing file, an unsupported extension (with the
// supported ones), a malformed PLY header (with its line) or truncated PLY
// body, an Assimp failure (with Assimp's reason; for an OBJ face index error
// also the line), an empty mesh, a non-finite coordinate (with the vertex
// index) and an index out of range.
Mesh load_mesh_file(const std::string& path);

// A file format of the mesh library: its name and extensions (".stl").
struct MeshFormat {
    std::string name;
    std::vector<std::string> extensions;
};
std::vector<MeshFormat> mesh_formats();

// Every supported extension, sorted, space-separated (".3d .3ds ... .zgl").
std::string mesh_extensions();

// Where load_mesh_file's warnings go (a message naming the file and line);
// by default "warning: MESSAGE" on stderr. An empty handler restores that.
void set_mesh_warning_handler(std::function<void(const std::string&)> handler);

// The Utah teapot: Newell's 32 bicubic Bezier patches, each tessellated into
// t x t quads of two triangles; triangles that collapse at the lid and bottom
// poles are dropped, so t = 6 gives 2,256 triangles (the technical report's
// teapot has 2,262). Y is up. Not normalised. t in [1, 256].
Mesh make_teapot(int tessellation = 6);

// Diffuse, mirror and glass (ior 1.5) UV spheres of 8,192 triangles each
// over a floor quad: 24,578 triangles, the count of the report's 'Spheres'.
// materials[0] is the floor. Y is up. Not normalised.
Mesh make_spheres();

// A closed unit UV sphere (pole triangle fans) of about approx_triangles
// triangles (at least 6; relative error below 1% from 1,000 up).
// Throws InputError for 0 or more than 200,000,000.
Mesh make_uv_sphere(std::size_t approx_triangles);

// "teapot" | "spheres" | "sphere:N" | a mesh file path. The result is
// normalised with normalize_to_cube and named after the spec.
// Throws InputError naming the spec when it is malformed.
Mesh make_scene(const std::string& spec);

// Uniform scale and translation so the bounds are centred on the origin and
// the largest extent spans exactly [-1,1]; every vertex ends in [-1,1]^3.
// Throws InputError for a mesh without vertices or with zero extent.
void normalize_to_cube(Mesh& m);

}  // namespace pluecker
