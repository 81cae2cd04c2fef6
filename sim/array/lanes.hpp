// SPDX-License-Identifier: MIT
// Lane fields of the array's ports: rtl/pluecker_array.sv puts lane l of
// every port in bits [l*W +: W] (W the intersector port's width), so a
// Verilated port (a plain integer up to 64 bits or a VlWide word array)
// holds N fields of W bits side by side.
#pragma once

#include "rtl_stream.hpp"

#include <array>
#include <cstddef>
#include <cstdint>
#include <type_traits>

namespace pluecker::sim {

constexpr std::uint64_t low_mask(int width) {
    return width >= 64 ? ~std::uint64_t{0} : (std::uint64_t{1} << width) - 1;
}

// Bits [lsb, lsb + width) of a port, width 1..32.
template <class Port>
std::uint32_t get_bits(const Port& p, int lsb, int width) {
    if constexpr (VlIsVlWide<Port>::value) {
        const int w = lsb / 32, s = lsb % 32;
        std::uint64_t v = static_cast<std::uint64_t>(p.m_storage[w]) >> s;
        if (s + width > 32) v |= static_cast<std::uint64_t>(p.m_storage[w + 1]) << (32 - s);
        return static_cast<std::uint32_t>(v & low_mask(width));
    } else {
        static_assert(std::is_integral_v<Port>, "narrow ports are integers");
        return static_cast<std::uint32_t>((static_cast<std::uint64_t>(p) >> lsb) & low_mask(width));
    }
}

// Sets bits [lsb, lsb + width) of a port to v (width 1..32, v below 2^width).
template <class Port>
void set_bits(Port& p, int lsb, int width, std::uint32_t v) {
    const std::uint64_t m = low_mask(width);
    if constexpr (VlIsVlWide<Port>::value) {
        const int w = lsb / 32, s = lsb % 32;
        const std::uint64_t cur = static_cast<std::uint64_t>(p.m_storage[w]) |
                                  (s + width > 32 ? static_cast<std::uint64_t>(p.m_storage[w + 1]) << 32 : 0);
        const std::uint64_t next = (cur & ~(m << s)) | ((v & m) << s);
        p.m_storage[w] = static_cast<std::uint32_t>(next);
        if (s + width > 32) p.m_storage[w + 1] = static_cast<std::uint32_t>(next >> 32);
    } else {
        static_assert(std::is_integral_v<Port>, "narrow ports are integers");
        const auto cur = static_cast<std::uint64_t>(p);
        p = static_cast<Port>((cur & ~(m << lsb)) | ((v & m) << lsb));
    }
}

// Lane `lane` of a port whose lanes are `width` bits wide, set to a port
// value of the contract's encoding (32-bit words, least significant first).
template <class Port, std::size_t N>
void set_lane(Port& p, int lane, int width, const std::array<std::uint32_t, N>& words) {
    for (int k = 0; k * 32 < width; ++k) {
        const int bits = width - k * 32 < 32 ? width - k * 32 : 32;
        set_bits(p, lane * width + k * 32, bits, words[static_cast<std::size_t>(k)]);
    }
}

// Every lane of a port to zero.
template <class Port>
void clear(Port& p) {
    if constexpr (VlIsVlWide<Port>::value) {
        for (std::size_t k = 0; k < Port::Words; ++k) p.m_storage[k] = 0;
    } else {
        p = 0;
    }
}

// One bit of a port (a valid, ready or hit lane).
template <class Port>
bool get_bit(const Port& p, int bit) {
    return get_bits(p, bit, 1) != 0;
}

template <class Port>
void set_bit(Port& p, int bit, bool v) {
    set_bits(p, bit, 1, v ? 1u : 0u);
}

}  // namespace pluecker::sim
