// SPDX-License-Identifier: MIT
// Shared by the fixed-point test suites (test_fixed, test_extremes,
// test_margin_bound): the long-run switch, a format from two widths, and the
// tally of fixed-point answers against exact ones.
#pragma once

#include "pluecker/fixed.hpp"

#include <cstddef>
#include <cstdlib>
#include <string>

namespace pluecker::test_support {

// PLUECKER_LONG=1 (make sim-regress) selects the full-size suites.
inline bool long_run() {
    const char* e = std::getenv("PLUECKER_LONG");
    return e && *e && std::string(e) != "0";
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

}  // namespace pluecker::test_support
