// SPDX-License-Identifier: MIT
// libFuzzer target: query text through read_queries and every box test.
//
// Findings (abort): any exception other than InputError; an InputError that
// does not name the source and a line that exists; a query read_queries
// accepts but validate_query rejects; a write_query/read_queries round trip
// that changes a bit; a fixed-point range error that is not about the range;
// the conservative fixed-point test missing a box the exact test hits (the
// no-miss guarantee of fixed.hpp, from any finite origin); a valid query
// whose ray the fixed-point set-up rejects (every finite origin is taken);
// a clipped origin off the range. The fixed-point format (widths, mode) is
// picked from a checksum of the input, so every width pair gets exercised.
#include "pluecker/boxtest.hpp"
#include "pluecker/fixed.hpp"
#include "pluecker/query.hpp"

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <optional>
#include <sstream>
#include <string>
#include <vector>

namespace {

using namespace pluecker;

constexpr std::size_t kMaxQueries = 64;

bool same_bits(float a, float b) { return std::memcmp(&a, &b, sizeof a) == 0; }

bool same_query(const Query& a, const Query& b) {
    for (int k = 0; k < 3; ++k)
        if (!same_bits(a.ray.o[k], b.ray.o[k]) || !same_bits(a.ray.d[k], b.ray.d[k]) ||
            !same_bits(a.box.lo[k], b.box.lo[k]) || !same_bits(a.box.hi[k], b.box.hi[k]))
            return false;
    return same_bits(a.ray.tmax, b.ray.tmax);
}

FixedFormat format_for(const std::uint8_t* data, std::size_t size) {
    std::uint32_t h = 2166136261u;  // FNV-1a
    for (std::size_t i = 0; i < size; ++i) h = (h ^ data[i]) * 16777619u;
    FixedFormat f;
    const int span = FixedFormat::kMaxBits - FixedFormat::kMinBits + 1;
    f.coord_bits = FixedFormat::kMinBits + static_cast<int>(h % span);
    f.dir_bits = FixedFormat::kMinBits + static_cast<int>((h / span) % span);
    f.mode = (h >> 24) & 1 ? FixedMode::Nearest : FixedMode::Conservative;
    return f;
}

void check_error(const InputError& e, std::size_t line_count) {
    const std::string msg = e.what();
    if (msg.rfind("fuzz:", 0) != 0) std::abort();
    const std::size_t line = std::strtoul(msg.c_str() + 5, nullptr, 10);
    if (line == 0 || line > line_count + 1) std::abort();
}

void check_fixed(const Query& q, const FixedFormat& f, bool exact) {
    std::optional<FixedRay> fr;
    try {
        fr = fixed_setup_ray(q.ray, f);
    } catch (const InputError&) {
        std::abort();  // validate_query accepted it: every such ray is taken
    }
    if (fr)
        for (int a = 0; a < 3; ++a)
            if (fr->org[a] < f.coord_min() || fr->org[a] > f.coord_max()) std::abort();
    FixedBox fb;
    try {
        fb = fixed_quantize_box(q.box, f);
    } catch (const InputError& e) {
        if (!std::strstr(e.what(), "outside the fixed-point range")) std::abort();
        return;
    }
    const bool hit = fr && fixed_hit(*fr, fb, f);
    if (hit != fixed_hit(q.ray, q.box, f)) std::abort();
    if (f.mode == FixedMode::Conservative && exact && !hit) std::abort();
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    const std::string text(reinterpret_cast<const char*>(data), size);
    const std::size_t line_count = static_cast<std::size_t>(std::count(text.begin(), text.end(), '\n'));
    std::vector<Query> qs;
    std::vector<std::size_t> lines;
    try {
        std::istringstream in(text);
        qs = read_queries(in, "fuzz", &lines);
    } catch (const InputError& e) {
        check_error(e, line_count);
        return 0;
    }
    if (lines.size() != qs.size()) std::abort();
    for (std::size_t i = 1; i < lines.size(); ++i)
        if (lines[i] <= lines[i - 1]) std::abort();

    const FixedFormat f = format_for(data, size);
    std::ostringstream written;
    const std::size_t n = std::min(qs.size(), kMaxQueries);
    for (std::size_t i = 0; i < n; ++i) {
        const Query& q = qs[i];
        try {
            validate_query(q, "again");
        } catch (const InputError&) {
            std::abort();
        }
        write_query(written, q);
        const bool exact = exact_hit(q.ray, q.box);
        (void)smits_hit(smits_setup(q.ray), q.box);
        (void)pluecker_hit(pluecker_setup(q.ray), q.box);
        check_fixed(q, f, exact);
    }
    std::istringstream back(written.str());
    const std::vector<Query> again = read_queries(back, "round trip");
    if (again.size() != n) std::abort();
    for (std::size_t i = 0; i < n; ++i)
        if (!same_query(again[i], qs[i])) std::abort();
    return 0;
}
