// SPDX-License-Identifier: MIT
// `pluecker_sim_local render`: the model's batched render path with every box
// query answered by the local unit's RTL (hardware in the loop), each answer
// checked against the golden model. Scene, camera and image options are
// those of `pluecker render` (pluecker/app/render_options.hpp), so the image
// equals `pluecker render --test local` with the same options and widths.
#include "commands.hpp"
#include "hil_render.hpp"
#include "local_engine.hpp"

#include <cstdio>
#include <optional>

namespace pluecker::sim {
namespace {

constexpr const char* kUsage =
    "usage: pluecker_sim_local render [options of 'pluecker render'] [--out IMG.png] [--stats STATS.json]\n"
    "Renders like 'pluecker render --test local' (same options and defaults, see\n"
    "'pluecker render --help'), through the model's batched traversal with --pool rays\n"
    "in flight; every batch of box queries is streamed back to back through the RTL (with\n"
    "CHILDREN = 2 a node's two child boxes in one query) and each answer is compared with\n"
    "the golden model (local_hit on the query's node ray). --test may only be local;\n"
    "--mode, --box-bits, --dir-bits and --grid-bits default to (and must match) the build.\n"
    "  --out FILE     PNG image                                        [render.png]\n"
    "  --stats FILE   the statistics of 'pluecker render' plus an \"rtl\" section\n"
    "  --quiet        no progress on stderr\n"
    "exit status: 0 ok, 1 mismatch or RTL protocol error, 2 bad input or options\n";

}  // namespace

int cmd_render(const std::vector<std::string>& argv) {
    // The build's configuration fills in what the command line leaves out.
    const LocalFormat built = built_local_format();
    const std::optional<app::Args> a = render_args(argv, kUsage, "local", check_build_options,
                                                   {{"box-bits", std::to_string(built.box_bits)},
                                                  {"dir-bits", std::to_string(built.dir_bits)},
                                                  {"grid-bits", std::to_string(built.grid_bits)},
                                                  {"mode", mode_name(built.mode)}});
    if (!a) return 0;
    const auto s = batched_setup(*a);

    RtlLocal rtl;
    RtlLocalEngine engine(rtl);
    RenderStats st;
    const StreamStats& rs = rtl.stats();
    auto qps = [&] {
        return engine.rtl_seconds() > 0 ? static_cast<double>(engine.box_tests()) / engine.rtl_seconds() : 0.0;
    };
    const double seconds = render_through(*s, *a, engine, st, [&](double wall) {
        nlohmann::json j = rtl_section("pluecker_sim_local", engine.box_tests(), engine.batches(),
                                       engine.mismatches(), engine.rtl_seconds(), rs, wall);
        j["children"] = kChildren;
        j["rtl_queries"] = engine.rtl_queries();
        j["paired_queries"] = engine.paired();
        return j;
    });
    std::printf("render %s %dx%d (%s, order %s, build %s): %llu box queries in %llu RTL queries (%llu with two "
                "children) in %llu batches, %llu cycles, %.3f M box queries/s in the RTL loop, %.2f s in all, %llu "
                "mismatches\n",
                s->mesh.name.c_str(), s->opts.width, s->opts.height, build_name().c_str(), order_name(s->opts.order),
                method_name(s->build), static_cast<unsigned long long>(engine.box_tests()),
                static_cast<unsigned long long>(engine.rtl_queries()),
                static_cast<unsigned long long>(engine.paired()), static_cast<unsigned long long>(engine.batches()),
                static_cast<unsigned long long>(rs.cycles), qps() / 1e6, seconds,
                static_cast<unsigned long long>(engine.mismatches()));
    return engine.mismatches() == 0 ? 0 : 1;
}

}  // namespace pluecker::sim
