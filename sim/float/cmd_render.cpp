// SPDX-License-Identifier: MIT
// `pluecker_sim render` of a binary32 unit: the model's batched render path
// on the float BVH with every box query answered by the unit's RTL
// (hardware in the loop), each answer checked against the unit's model.
// Scene, camera and image options are those of `pluecker render`, so the
// image equals `pluecker render --test f32-pluecker|f32-pluecker-cons|f32-smits`
// (the build's unit) with the same options.
#include "float_rtl.hpp"
#include "hil_render.hpp"
#include "rtl_engine.hpp"

#include "pluecker/batched.hpp"

#include <cstdio>
#include <optional>
#include <string>
#include <vector>

namespace pluecker::sim {
namespace {

constexpr const char* kUsage =
    "usage: pluecker_sim render [options of 'pluecker render'] [--out IMG.png] [--stats STATS.json]\n"
    "Renders like 'pluecker render --test <the built unit>' (f32-pluecker, f32-pluecker-cons\n"
    "or f32-smits; same options and defaults, see 'pluecker render --help'), through the\n"
    "model's batched traversal of the float BVH with --pool rays in flight; every batch\n"
    "of box queries is streamed back to back through the RTL and each answer is compared\n"
    "with the unit's model (f32unit.hpp).\n"
    "  --out FILE     PNG image                                        [render.png]\n"
    "  --stats FILE   the statistics of 'pluecker render' plus an \"rtl\" section\n"
    "  --quiet        no progress on stderr\n"
    "exit status: 0 ok, 1 mismatch or RTL protocol error, 2 bad input or options\n";

}  // namespace

int cmd_render(const std::vector<std::string>& argv) {
    // The unit has no build options a render could contradict but its test.
    const std::optional<app::Args> a = render_args(argv, kUsage, test_name(kBuiltTest), [](const app::Args&) {}, {});
    if (!a) return 0;
    const auto s = batched_setup(*a);

    FloatRtl rtl;
    RtlBoxEngine<F32BoxQuery<kBuiltTest>, FloatRtl, PackedQuery> engine(
        rtl, [](const F32BoxQuery<kBuiltTest>& q) { return pack(q.unit); },
        [](const F32BoxQuery<kBuiltTest>& q) { return model_hit(q.unit); });
    RenderStats st;
    const StreamStats& rs = rtl.stats();
    const double seconds = render_through(*s, *a, engine, st, [&](double wall) {
        nlohmann::json j = rtl_section("pluecker_sim", engine.queries(), engine.batches(), engine.mismatches(),
                                       engine.rtl_seconds(), rs, wall);
        j["unit"] = build_name();
        return j;
    });
    std::printf("render %s %dx%d (%s, order %s, build %s): %llu box queries in %llu batches through the RTL, "
                "%llu cycles, %.3f M queries/s in the RTL loop, %.2f s in all, %llu mismatches\n",
                s->mesh.name.c_str(), s->opts.width, s->opts.height, build_name().c_str(), order_name(s->opts.order),
                method_name(s->build), static_cast<unsigned long long>(engine.queries()),
                static_cast<unsigned long long>(engine.batches()), static_cast<unsigned long long>(rs.cycles),
                engine.queries_per_second() / 1e6, seconds, static_cast<unsigned long long>(engine.mismatches()));
    return engine.mismatches() == 0 ? 0 : 1;
}

}  // namespace pluecker::sim
