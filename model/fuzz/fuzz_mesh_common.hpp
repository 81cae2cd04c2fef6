// SPDX-License-Identifier: MIT
// Shared body of the mesh fuzz targets (fuzz_mesh_obj, fuzz_mesh_ply).
//
// The loader reads a path, so each input is written to a file in a private
// temporary directory (made once per process, so an OBJ's mtllib can only
// name files the fuzzer itself wrote there) and loaded from there. An
// InputError is the expected answer to bad bytes; any other exception, a
// crash, a leak or undefined behaviour is a finding. A mesh that loads is
// pushed through the rest of the pipeline the renderer uses: normalisation,
// both BVH builds, the float and fixed-point traversals of a few rays.
#pragma once

#include "pluecker/bvh.hpp"
#include "pluecker/fixed.hpp"
#include "pluecker/mesh.hpp"
#include "pluecker/traverse.hpp"

#include <unistd.h>

#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <string>

namespace pluecker::fuzz {

// The private directory, made on first use and removed at exit.
inline const std::string& temp_dir() {
    static const std::string dir = [] {
        char templ[] = "/tmp/pluecker_fuzz_XXXXXX";
        const char* d = ::mkdtemp(templ);
        if (!d) std::abort();
        return std::string(d);
    }();
    static const bool cleanup = [] {
        std::atexit([] {
            std::error_code ec;
            std::filesystem::remove_all(temp_dir(), ec);
        });
        return true;
    }();
    (void)cleanup;
    return dir;
}

inline std::string temp_path(const char* ext) { return temp_dir() + "/input" + ext; }

inline void write_file(const std::string& path, const std::uint8_t* data, std::size_t size) {
    std::FILE* f = std::fopen(path.c_str(), "wb");
    if (!f) std::abort();
    if (size && std::fwrite(data, 1, size, f) != size) std::abort();
    std::fclose(f);
}

// A few rays through the normalised scene, every box test, both orders the
// fixed path allows.
inline void exercise(const Mesh& mesh) {
    const Ray rays[] = {
        {Vec3(0.0f, 0.0f, 3.0f), Vec3(0.0f, 0.0f, -1.0f), kInf},
        {Vec3(-3.0f, 0.1f, 0.2f), Vec3(1.0f, 0.0f, 0.0f), kInf},
        {Vec3(0.3f, 3.0f, -0.2f), Vec3(-0.1f, -1.0f, 0.05f), 4.0f},
        {Vec3(0.0f), Vec3(1.0f, 1.0f, 1.0f), kInf},
        {Vec3(0.5f, -0.5f, 0.25f), Vec3(-0.0f, 0.0f, 1.0f), 0.5f},
    };
    for (BuildMethod m : {BuildMethod::Sah, BuildMethod::Median}) {
        BuildOptions bo;
        bo.method = m;
        const Bvh bvh = build_bvh(mesh, bo);
        if (bvh.tri_order.size() != mesh.triangles.size()) std::abort();
        Accel accel(mesh, bvh);
        for (BoxTestKind t : {BoxTestKind::Smits, BoxTestKind::Pluecker}) {
            const auto tracer = make_tracer(accel, t, ChildOrder::Dsa);
            for (const Ray& r : rays) {
                TraversalStats st;
                const Hit h = tracer->closest(r, st);
                if (h.found() && h.tri >= mesh.triangles.size()) std::abort();
                tracer->occluded(r, st);
            }
        }
        FixedFormat f;
        f.coord_bits = 8;
        f.dir_bits = 8;
        accel.quantize(f);
        const auto fixed = make_tracer(accel, BoxTestKind::Fixed, ChildOrder::Dsa);
        for (const Ray& r : rays) {
            TraversalStats st;
            const Hit h = fixed->closest(r, st);
            if (h.found() && h.tri >= mesh.triangles.size()) std::abort();
        }
    }
}

inline int run_mesh(const std::uint8_t* data, std::size_t size, const char* ext) {
    const std::string path = temp_path(ext);
    write_file(path, data, size);
    Mesh mesh;
    try {
        mesh = load_mesh_file(path);
    } catch (const InputError& e) {
        // The message must name the file.
        if (std::string(e.what()).find(path) == std::string::npos) std::abort();
        return 0;
    }
    if (mesh.triangles.empty() || mesh.vertices.empty()) std::abort();  // must have been an InputError
    if (mesh.tri_material.size() != mesh.triangles.size() || mesh.materials.empty()) std::abort();
    for (const auto& t : mesh.triangles)
        for (std::uint32_t i : t)
            if (i >= mesh.vertices.size()) std::abort();
    for (std::uint16_t m : mesh.tri_material)
        if (m >= mesh.materials.size()) std::abort();
    try {
        normalize_to_cube(mesh);  // zero extent (all vertices equal) is an InputError
    } catch (const InputError&) {
        return 0;
    }
    exercise(mesh);
    return 0;
}

}  // namespace pluecker::fuzz
