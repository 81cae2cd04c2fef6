// SPDX-License-Identifier: MIT
// libFuzzer target: PLY bytes (ASCII or binary) through load_mesh_file and
// the BVH/traversal.
#include "fuzz_mesh_common.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    return pluecker::fuzz::run_mesh(data, size, ".ply");
}
