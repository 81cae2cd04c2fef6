// SPDX-License-Identifier: MIT
// Shared by the fixed-point test suites (test_fixed, test_extremes,
// test_margin_bound): the long-run switch, a format from two widths, the
// tally of fixed-point answers against exact ones, and the box and ray
// lattices of the exhaustive domains.
#pragma once

#include "pluecker/fixed.hpp"
#include "pluecker/geometry.hpp"

#include <cstddef>
#include <cstdlib>
#include <optional>
#include <stdexcept>
#include <span>
#include <string>
#include <utility>
#include <vector>

namespace pluecker::test_support {

// PLUECKER_LONG=1 (make sim-regress) selects the full-size suites.
inline bool long_run() {
    const char* e = std::getenv("PLUECKER_LONG");
    return e && *e && std::string(e) != "0";
}

// fixed_setup_ray for a ray that meets the range cube (every ray of these
// suites starts inside it); std::logic_error when it does not.
inline FixedRay setup_ray(const Ray& r, const FixedFormat& f) {
    const std::optional<FixedRay> fr = fixed_setup_ray(r, f);
    if (!fr) throw std::logic_error("test ray never meets the range cube");
    return *fr;
}

inline FixedFormat format(int c, int d, FixedMode m = FixedMode::Conservative) {
    FixedFormat f;
    f.coord_bits = c;
    f.dir_bits = d;
    f.mode = m;
    return f;
}

// Fixed-point answers against exact ones.
struct Tally {
    std::size_t queries = 0, real_hits = 0, false_misses = 0, false_hits = 0;
    void add(bool exact, bool fixed) {
        ++queries;
        real_hits += exact;
        false_misses += exact && !fixed;
        false_hits += !exact && fixed;
    }
    void add(const Tally& t) {
        queries += t.queries;
        real_hits += t.real_hits;
        false_misses += t.false_misses;
        false_hits += t.false_hits;
    }
    // False hits as a share of the real misses.
    double false_hit_rate() const {
        const std::size_t misses = queries - real_hits;
        return misses ? double(false_hits) / double(misses) : 0.0;
    }
};

// Every box whose planes on each axis are two of `planes` (lo index <= hi
// index), the x slab outermost, then y, then z.
inline std::vector<Box> lattice_boxes(std::span<const float> planes) {
    std::vector<std::pair<float, float>> slabs;
    for (std::size_t l = 0; l < planes.size(); ++l)
        for (std::size_t h = l; h < planes.size(); ++h) slabs.emplace_back(planes[l], planes[h]);
    std::vector<Box> boxes;
    for (auto [lx, hx] : slabs)
        for (auto [ly, hy] : slabs)
            for (auto [lz, hz] : slabs) {
                Box b;
                b.lo = Vec3(lx, ly, lz);
                b.hi = Vec3(hx, hy, hz);
                boxes.push_back(b);
            }
    return boxes;
}

// Calls visit(ray) for every ray with origin coordinates from `coords`,
// direction components from `dirs` (not all zero) and tmax from `tmaxes`;
// nested in the order ox, oy, oz, dx, dy, dz, tmax.
template <class Visit>
void for_each_lattice_ray(std::span<const float> coords, std::span<const float> dirs, std::span<const float> tmaxes,
                          Visit&& visit) {
    for (float ox : coords)
        for (float oy : coords)
            for (float oz : coords)
                for (float dx : dirs)
                    for (float dy : dirs)
                        for (float dz : dirs) {
                            if (dx == 0 && dy == 0 && dz == 0) continue;
                            for (float tm : tmaxes) {
                                Ray r;
                                r.o = Vec3(ox, oy, oz);
                                r.d = Vec3(dx, dy, dz);
                                r.tmax = tm;
                                visit(r);
                            }
                        }
}

}  // namespace pluecker::test_support
