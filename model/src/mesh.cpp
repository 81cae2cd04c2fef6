// SPDX-License-Identifier: MIT
// Mesh bounds, normalisation into the scene cube, and OBJ/PLY loading.
#include "pluecker/mesh.hpp"

#include <assimp/Importer.hpp>
#include <assimp/material.h>
#include <assimp/postprocess.h>
#include <assimp/scene.h>

#include <glm/common.hpp>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <filesystem>
#include <limits>
#include <sstream>

namespace pluecker {

Box Mesh::bounds() const {
    Box b;
    for (const Vec3& v : vertices) b.grow(v);
    return b;
}

void normalize_to_cube(Mesh& m) {
    if (m.vertices.empty()) throw InputError(m.name + ": empty mesh, cannot normalise");
    const Box b = m.bounds();
    const Vec3 e = b.extent();
    const double ext = std::max({double(e.x), double(e.y), double(e.z)});
    if (!(ext > 0.0) || !std::isfinite(ext))
        throw InputError(m.name + ": mesh has zero or non-finite extent, cannot normalise");
    // In double: the centre and lo - c are exact, so the largest axis lands on
    // exactly -1 and +1 after rounding to float; the clamp only guards the
    // other axes against a last-ulp overshoot.
    const double s = 2.0 / ext;
    double c[3];
    for (int a = 0; a < 3; ++a) c[a] = 0.5 * (double(b.lo[a]) + double(b.hi[a]));
    for (Vec3& v : m.vertices)
        for (int a = 0; a < 3; ++a) {
            const float x = static_cast<float>((double(v[a]) - c[a]) * s);
            v[a] = std::clamp(x, -1.0f, 1.0f);
        }
}

namespace {

std::string lower_extension(const std::string& path) {
    std::string ext = std::filesystem::path(path).extension().string();
    for (char& ch : ext) ch = static_cast<char>(std::tolower(static_cast<unsigned char>(ch)));
    return ext;
}

void check_readable(const std::string& path) {
    std::error_code ec;
    const auto st = std::filesystem::status(path, ec);
    if (!std::filesystem::exists(st)) throw InputError(path + ": no such file");
    if (!std::filesystem::is_regular_file(st)) throw InputError(path + ": not a regular file");
    const std::string ext = lower_extension(path);
    if (ext != ".obj" && ext != ".ply")
        throw InputError(path + ": unknown mesh extension '" + ext + "' (expected .obj or .ply)");
    if (std::filesystem::file_size(path, ec) == 0) throw InputError(path + ": empty mesh (empty file)");
}

// Checked before any post-processing step runs, so a NaN never reaches
// Assimp's vertex welding. Indices are those of Assimp's raw import: for a
// PLY file, the file's vertex index; for OBJ, one vertex per face corner.
void check_finite(const aiScene& sc, const std::string& path) {
    for (unsigned mi = 0; mi < sc.mNumMeshes; ++mi) {
        const aiMesh& am = *sc.mMeshes[mi];
        for (unsigned vi = 0; vi < am.mNumVertices; ++vi) {
            const aiVector3D& p = am.mVertices[vi];
            if (std::isfinite(p.x) && std::isfinite(p.y) && std::isfinite(p.z)) continue;
            std::ostringstream os;
            os << path << ": non-finite coordinate at vertex " << vi;
            if (sc.mNumMeshes > 1) os << " of mesh " << mi;
            os << " (" << p.x << ' ' << p.y << ' ' << p.z << ')';
            throw InputError(os.str());
        }
    }
}

Material to_material(const aiMaterial& am) {
    Material m;
    aiString name;
    if (am.Get(AI_MATKEY_NAME, name) == AI_SUCCESS && std::string(name.C_Str()) == AI_DEFAULT_MATERIAL_NAME)
        return m;
    aiColor3D c;
    if (am.Get(AI_MATKEY_COLOR_DIFFUSE, c) == AI_SUCCESS) m.color = Vec3(c.r, c.g, c.b);
    float opacity = 1.0f;
    if (am.Get(AI_MATKEY_OPACITY, opacity) == AI_SUCCESS && opacity < 1.0f) {
        m.kind = MaterialKind::Glass;
        float ior = 0.0f;
        if (am.Get(AI_MATKEY_REFRACTI, ior) == AI_SUCCESS && ior >= 1.0f) m.ior = ior;
    }
    return m;
}

void append_mesh(Mesh& out, const aiMesh& am, const std::string& path) {
    const std::size_t base = out.vertices.size();
    if (base + am.mNumVertices > std::numeric_limits<std::uint32_t>::max())
        throw InputError(path + ": more than 2^32-1 vertices");
    for (unsigned vi = 0; vi < am.mNumVertices; ++vi)
        out.vertices.emplace_back(am.mVertices[vi].x, am.mVertices[vi].y, am.mVertices[vi].z);
    const auto mat = static_cast<std::uint16_t>(am.mMaterialIndex);
    for (unsigned fi = 0; fi < am.mNumFaces; ++fi) {
        const aiFace& f = am.mFaces[fi];
        if (f.mNumIndices != 3) continue;  // points and lines (triangulation leaves no polygons)
        std::array<std::uint32_t, 3> t{};
        for (int k = 0; k < 3; ++k) {
            if (f.mIndices[k] >= am.mNumVertices) {
                std::ostringstream os;
                os << path << ": vertex index " << f.mIndices[k] << " out of range (" << am.mNumVertices
                   << " vertices) in face " << fi;
                throw InputError(os.str());
            }
            t[k] = static_cast<std::uint32_t>(base + f.mIndices[k]);
        }
        out.triangles.push_back(t);
        out.tri_material.push_back(mat);
    }
}

}  // namespace

Mesh load_mesh_file(const std::string& path) {
    check_readable(path);
    Assimp::Importer imp;
    // Step 1: raw import, no post-processing, so non-finite input can be
    // reported before anything else touches it.
    const aiScene* sc = imp.ReadFile(path, 0);
    if (!sc) throw InputError(path + ": cannot load mesh: " + imp.GetErrorString());
    check_finite(*sc, path);
    // Step 2: Triangulate splits an n-gon into n-2 triangles in place of the
    // polygon and keeps zero-area ones; JoinIdenticalVertices only renumbers
    // vertices. FindDegenerates is deliberately not run, so no triangle is
    // dropped and ids follow the file's face order within each mesh.
    sc = imp.ApplyPostProcessing(aiProcess_Triangulate | aiProcess_JoinIdenticalVertices);
    if (!sc) throw InputError(path + ": cannot load mesh: " + imp.GetErrorString());
    if (sc->mNumMaterials > std::numeric_limits<std::uint16_t>::max())
        throw InputError(path + ": more than 65535 materials");

    Mesh m;
    m.name = path;
    for (unsigned i = 0; i < sc->mNumMaterials; ++i) m.materials.push_back(to_material(*sc->mMaterials[i]));
    if (m.materials.empty()) m.materials.emplace_back();
    for (unsigned mi = 0; mi < sc->mNumMeshes; ++mi) {
        const aiMesh& am = *sc->mMeshes[mi];
        if (am.mMaterialIndex >= m.materials.size()) {
            std::ostringstream os;
            os << path << ": material index " << am.mMaterialIndex << " out of range in mesh " << mi;
            throw InputError(os.str());
        }
        append_mesh(m, am, path);
    }
    if (m.vertices.empty() || m.triangles.empty()) throw InputError(path + ": empty mesh (no triangles)");
    return m;
}

}  // namespace pluecker
