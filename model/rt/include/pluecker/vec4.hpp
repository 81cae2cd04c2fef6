// SPDX-License-Identifier: MIT
// Four-lane float vectors for the traversal kernels (GCC/Clang vector
// extensions: SSE on x86-64, NEON on aarch64, scalar code elsewhere). Only
// lane-wise IEEE operations and shuffles, so a kernel built on them gives
// the same bits as the scalar code it mirrors.
#pragma once

#include <bit>
#include <cstdint>
#include <cstring>

#if defined(__SSE__)
#include <xmmintrin.h>
#endif

namespace pluecker {

typedef float Float4 __attribute__((vector_size(16)));
typedef std::int32_t Int4 __attribute__((vector_size(16)));

[[gnu::always_inline]] inline Float4 splat4(float f) { return Float4{f, f, f, f}; }
// 16 bytes from p, any alignment.
[[gnu::always_inline]] inline Float4 load4(const float* p) {
    Float4 v;
    std::memcpy(&v, p, sizeof v);
    return v;
}
[[gnu::always_inline]] inline Float4 swap_halves(Float4 v) { return __builtin_shufflevector(v, v, 2, 3, 0, 1); }
// Bit i set when lane i is true (all ones).
[[gnu::always_inline]] inline unsigned lane_bits(Int4 m) {
#if defined(__SSE__)
    return static_cast<unsigned>(_mm_movemask_ps(std::bit_cast<__m128>(m)));
#else
    return (m[0] & 1u) | (m[1] & 2u) | (m[2] & 4u) | (m[3] & 8u);
#endif
}

}  // namespace pluecker
