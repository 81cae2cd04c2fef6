// SPDX-License-Identifier: MIT
// Pieces the port contracts (contract.cpp, local_contract.cpp) share: the
// fields of a port value in 32-bit words, and the runs of widths over which
// a contract's derived constants stay the same (its configuration classes).
#pragma once

#include "pluecker/contract.hpp"

#include <array>
#include <cstddef>
#include <cstdint>
#include <ostream>
#include <utility>
#include <vector>

namespace pluecker::detail {

// Writes the low `bits` (<= 32) of v at bit `lsb` of a port value (32-bit
// words, least significant first: PortWords or a wider array).
template <std::size_t N>
void put_field(std::array<std::uint32_t, N>& w, int lsb, int bits, std::uint64_t v) {
    v &= (std::uint64_t{1} << bits) - 1;
    const int word = lsb / 32, shift = lsb % 32;
    w[static_cast<std::size_t>(word)] |= static_cast<std::uint32_t>(v << shift);
    if (shift + bits > 32) w[static_cast<std::size_t>(word) + 1] |= static_cast<std::uint32_t>(v >> (32 - shift));
}

// Reads `bits` (<= 32) at bit `lsb` of a port value.
template <std::size_t N>
std::uint64_t get_field(const std::array<std::uint32_t, N>& w, int lsb, int bits) {
    const int word = lsb / 32, shift = lsb % 32;
    std::uint64_t v = w[static_cast<std::size_t>(word)] >> shift;
    if (shift + bits > 32) v |= static_cast<std::uint64_t>(w[static_cast<std::size_t>(word) + 1]) << (32 - shift);
    return v & ((std::uint64_t{1} << bits) - 1);
}

// A field read back as a two's complement or unsigned value.
template <std::size_t N>
std::int64_t field_value(const std::array<std::uint32_t, N>& w, int lsb, int bits, bool is_signed) {
    auto x = static_cast<std::int64_t>(get_field(w, lsb, bits));
    if (is_signed && (x >> (bits - 1)) != 0) x -= std::int64_t{1} << bits;
    return x;
}

// Maximal runs lo..hi of the widths in [first, last] over which
// signature(width) stays the same (signature returns a comparable value).
template <class Signature>
std::vector<std::pair<int, int>> width_runs(int first, int last, Signature signature) {
    std::vector<std::pair<int, int>> runs;
    auto prev = signature(first);
    int lo = first;
    for (int w = first + 1; w <= last + 1; ++w) {
        if (w <= last) {
            auto sig = signature(w);
            if (sig == prev) continue;
            prev = std::move(sig);
        }
        runs.emplace_back(lo, w - 1);
        lo = w;
    }
    return runs;
}

// One function of a generated contract package: `name`(k) is value(class
// k) for every class k, 0 for any other k.
template <class Classes, class Value>
void write_sv_table(std::ostream& s, const Classes& classes, const char* name, const char* type, const char* what,
                    Value value) {
    s << "\n  // " << what << " of class k.\n"
      << "  function automatic " << type << " " << name << "(input int k);\n"
      << "    case (k)\n";
    for (std::size_t k = 0; k < classes.size(); ++k) s << "      " << k << ": " << name << " = " << value(classes[k]) << ";\n";
    s << "      default: " << name << " = 0;\n"
      << "    endcase\n"
      << "  endfunction\n";
}

}  // namespace pluecker::detail
