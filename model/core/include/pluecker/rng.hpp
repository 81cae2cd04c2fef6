// SPDX-License-Identifier: MIT
// The project's one seeded generator: SplitMix64 (Steele, Lea & Flood,
// OOPSLA 2014), small, seedable and the same on every platform. Used by the
// query generators, the benchmarks and the seeded tests.
#pragma once

#include <cstdint>

namespace pluecker {

class Rng {
public:
    explicit Rng(std::uint64_t seed) : s_(seed) {}
    std::uint64_t next() {
        std::uint64_t z = (s_ += 0x9e3779b97f4a7c15ull);
        z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ull;
        z = (z ^ (z >> 27)) * 0x94d049bb133111ebull;
        return z ^ (z >> 31);
    }
    // Uniform integer in [0, n).
    std::uint32_t below(std::uint32_t n) { return static_cast<std::uint32_t>(next() % n); }
    bool coin() { return (next() >> 63) != 0; }
    // Uniform float in [0, 1) with 24 random bits (exact).
    float unit() { return static_cast<float>(next() >> 40) * 0x1p-24f; }
    // Uniform float in [-1, 1) (exact: -1 + k*2^-23).
    float sym() { return -1.0f + 2.0f * unit(); }
    float sign() { return coin() ? -1.0f : 1.0f; }

private:
    std::uint64_t s_;
};

}  // namespace pluecker
