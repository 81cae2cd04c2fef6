// SPDX-License-Identifier: MIT
// Stream options shared by the harnesses that drive several lanes at once
// (sim/array/, sim/cascade/): probabilities of --ready and --valid, and the
// options of their `check` command.
#pragma once

#include "pluecker/app/args.hpp"
#include "pluecker/geometry.hpp"  // InputError

#include <cstddef>
#include <cstdint>
#include <string>

namespace pluecker::sim {

// A probability option in (0, 1] (--ready, --valid); InputError otherwise.
inline double probability(const app::Args& args, const char* name, double fallback) {
    const double p = args.get_double(name, fallback);
    if (!(p > 0.0 && p <= 1.0))
        throw InputError(std::string("option --") + name + ": " + args.get(name, "") + " is outside (0, 1]");
    return p;
}

// The stream options of a harness: each output's ready high with
// probability `ready` a cycle, a lane with a query waiting offers it with
// probability `valid` (Rtl: ArrayRtl, CascadeRtl).
template <class Rtl>
void configure_stream(Rtl& rtl, double ready, double valid, std::uint64_t seed) {
    rtl.set_backpressure(ready, seed);
    rtl.set_idle(valid);
}

// The options of `check`: --n, --kind, --seed, --ready, --valid, --reset-every.
struct LaneCheckOptions {
    std::size_t n = 0;
    std::string kind;
    std::uint64_t seed = 0;
    double ready = 1.0, valid = 1.0;
    std::uint64_t reset_every = 0;  // 0: never, else at least 16 cycles
};

inline LaneCheckOptions lane_check_options(const app::Args& args) {
    LaneCheckOptions o;
    o.n = static_cast<std::size_t>(args.get_int("n", 200'000, 1, 10'000'000'000l));
    o.kind = args.get("kind", "mixed");
    o.seed = static_cast<std::uint64_t>(args.get_int("seed", 1, 0, 0x7fffffffffffffffl));
    o.ready = probability(args, "ready", 1.0);
    o.valid = probability(args, "valid", 1.0);
    o.reset_every = static_cast<std::uint64_t>(args.get_int("reset-every", 0, 0, 1'000'000'000'000l));
    if (o.reset_every != 0 && o.reset_every < 16)
        throw InputError("option --reset-every: " + std::to_string(o.reset_every) + " is below 16 cycles");
    return o;
}

}  // namespace pluecker::sim
