// SPDX-License-Identifier: MIT
#include "pluecker/app/names.hpp"

#include <string>
#include <vector>

namespace pluecker {

BoxTestKind parse_box_test(const std::string& s) {
    if (s == "exact") return BoxTestKind::Exact;
    if (s == "smits") return BoxTestKind::Smits;
    if (s == "pluecker") return BoxTestKind::Pluecker;
    if (s == "fixed") return BoxTestKind::Fixed;
    if (s == "local") return BoxTestKind::Local;
    if (s == "f32-pluecker") return BoxTestKind::F32Pluecker;
    if (s == "f32-pluecker-cons") return BoxTestKind::F32PlueckerCons;
    if (s == "f32-smits") return BoxTestKind::F32Smits;
    throw InputError("--test: '" + s +
                     "' is not one of exact, smits, pluecker, fixed, local, f32-pluecker, f32-pluecker-cons, f32-smits");
}

ChildOrder parse_child_order(const std::string& s) {
    if (s == "fixed") return ChildOrder::Fixed;
    if (s == "dsa") return ChildOrder::Dsa;
    if (s == "dist") return ChildOrder::Dist;
    throw InputError("--order: '" + s + "' is not one of fixed, dsa, dist");
}

BuildMethod parse_build_method(const std::string& s) {
    if (s == "median") return BuildMethod::Median;
    if (s == "sah") return BuildMethod::Sah;
    throw InputError("build method: '" + s + "' (expected median or sah)");
}

FixedMode parse_fixed_mode(const std::string& s) {
    if (s == "conservative") return FixedMode::Conservative;
    if (s == "nearest") return FixedMode::Nearest;
    throw InputError("mode '" + s + "' is not one of conservative, nearest");
}

MulStyle parse_mul_style(const std::string& s) {
    if (s == "auto") return MulStyle::Auto;
    if (s == "dsp") return MulStyle::Dsp;
    if (s == "lut") return MulStyle::Lut;
    if (s == "rom") return MulStyle::Rom;
    throw InputError("MUL_STYLE '" + s + "' is not one of auto, dsp, lut, rom");
}

FloatUnit parse_float_unit(const std::string& s) {
    if (s == "float") return FloatUnit::Pluecker;
    if (s == "smits") return FloatUnit::Smits;
    throw InputError("unit '" + s + "' is not one of float, smits");
}

// ---------------------------------------------------------------------------
// Widths

namespace {

int parse_bits(const std::string& s, const std::string& flag, const std::string& spec,
               int lo = FixedFormat::kMinBits, int hi = FixedFormat::kMaxBits) {
    if (s.empty() || s.size() > 3 || s.find_first_not_of("0123456789") != std::string::npos)
        throw InputError(flag + ": '" + s + "' in '" + spec + "' is not a width");
    const int v = std::stoi(s);
    if (v < lo || v > hi)
        throw InputError(flag + ": width " + s + " in '" + spec + "' is outside " + std::to_string(lo) + ".." +
                         std::to_string(hi));
    return v;
}

std::vector<std::string> split(const std::string& s, char sep) {
    std::vector<std::string> out;
    std::size_t pos = 0;
    for (;;) {
        const std::size_t k = s.find(sep, pos);
        out.push_back(s.substr(pos, k == std::string::npos ? std::string::npos : k - pos));
        if (k == std::string::npos) return out;
        pos = k + 1;
    }
}

// "A:B[:S]": A, A+S, ..., <= B.
std::vector<int> parse_range(const std::string& spec, const std::string& flag, int lo, int hi) {
    const auto parts = split(spec, ':');
    if (parts.size() < 2 || parts.size() > 3) throw InputError(flag + ": '" + spec + "' is not FIRST:LAST[:STEP]");
    const int a = parse_bits(parts[0], flag, spec, lo, hi);
    const int b = parse_bits(parts[1], flag, spec, lo, hi);
    int step = 1;
    if (parts.size() == 3) {
        const std::string& s = parts[2];
        if (s.empty() || s.size() > 2 || s.find_first_not_of("0123456789") != std::string::npos || std::stoi(s) < 1)
            throw InputError(flag + ": step '" + s + "' in '" + spec + "' is not a positive integer");
        step = std::stoi(s);
    }
    if (b < a) throw InputError(flag + ": '" + spec + "' has LAST < FIRST");
    std::vector<int> out;
    for (int w = a; w <= b; w += step) out.push_back(w);
    return out;
}

}  // namespace

std::vector<int> parse_bit_list(const std::string& spec, const std::string& flag, int lo, int hi) {
    if (spec.find(':') != std::string::npos) return parse_range(spec, flag, lo, hi);
    std::vector<int> out;
    for (const std::string& item : split(spec, ',')) out.push_back(parse_bits(item, flag, spec, lo, hi));
    return out;
}

std::vector<WidthPair> parse_widths(const std::string& spec, const std::string& flag) {
    std::vector<WidthPair> out;
    if (spec.find(':') != std::string::npos) {
        for (const int w : parse_range(spec, flag, FixedFormat::kMinBits, FixedFormat::kMaxBits)) out.push_back({w, w});
        return out;
    }
    for (const std::string& item : split(spec, ',')) {
        const std::size_t x = item.find('x');
        if (x == std::string::npos) {
            const int w = parse_bits(item, flag, spec);
            out.push_back({w, w});
        } else {
            out.push_back({parse_bits(item.substr(0, x), flag, spec), parse_bits(item.substr(x + 1), flag, spec)});
        }
    }
    return out;
}

}  // namespace pluecker
