// SPDX-License-Identifier: MIT
// `pluecker_sim render`: the model's batched render path with every box
// query answered by the RTL (hardware in the loop), each answer checked
// against the golden model. Scene, camera and image options are those of
// `pluecker render` (pluecker/app/render_options.hpp), so the image equals
// `pluecker render --test fixed` with the same options and widths.
#include "commands.hpp"
#include "hil_render.hpp"
#include "rtl_engine.hpp"
#include "rtl_intersector.hpp"

#include <cstdio>
#include <optional>

namespace pluecker::sim {
namespace {

constexpr const char* kUsage =
    "usage: pluecker_sim render [options of 'pluecker render'] [--out IMG.png] [--stats STATS.json]\n"
    "Renders like 'pluecker render --test fixed' (same options and defaults, see\n"
    "'pluecker render --help'), through the model's batched traversal with --pool rays\n"
    "in flight; every batch of box queries is streamed back to back through the RTL and\n"
    "each answer is compared with the golden model. --test may only be fixed; --mode,\n"
    "--coord-bits and --dir-bits default to (and must match) the build.\n"
    "  --out FILE     PNG image                                        [render.png]\n"
    "  --stats FILE   the statistics of 'pluecker render' plus an \"rtl\" section\n"
    "  --quiet        no progress on stderr\n"
    "exit status: 0 ok, 1 mismatch or RTL protocol error, 2 bad input or options\n";

}  // namespace

int cmd_render(const std::vector<std::string>& argv) {
    // The build's configuration fills in what the command line leaves out.
    const FixedFormat built = built_format();
    const std::optional<app::Args> a = render_args(argv, kUsage, "fixed", check_build_options,
                                                   {{"coord-bits", std::to_string(built.coord_bits)},
                                                  {"dir-bits", std::to_string(built.dir_bits)},
                                                  {"mode", mode_name(built.mode)}});
    if (!a) return 0;
    const auto s = batched_setup(*a);

    RtlIntersector rtl;
    RtlBoxEngine<BoxQuery, RtlIntersector, PackedQuery> engine(
        rtl, [](const BoxQuery& q) { return pack_query(q.ray, q.box); },
        [built](const BoxQuery& q) { return fixed_hit(q.ray, q.box, built); });
    RenderStats st;
    const StreamStats& rs = rtl.stats();
    const double seconds = render_through(*s, *a, engine, st, [&](double wall) {
        return rtl_section("pluecker_sim", engine.queries(), engine.batches(), engine.mismatches(),
                           engine.rtl_seconds(), rs, wall);
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
