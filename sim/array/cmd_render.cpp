// SPDX-License-Identifier: MIT
// `pluecker_sim_array render`: the model's batched render path with every
// box query answered by the array (hardware in the loop): each batch is
// spread over the lanes round-robin, each answer checked against the golden
// model. Scene, camera and image options are those of `pluecker render`, so
// the image equals `pluecker render --test fixed` with the same options and
// widths.
#include "commands.hpp"
#include "hil_render.hpp"
#include "rtl_engine.hpp"

#include <cstdio>
#include <optional>

namespace pluecker::sim {
namespace {

constexpr const char* kUsage =
    "usage: pluecker_sim_array render [options of 'pluecker render'] [--out IMG.png] [--stats STATS.json]\n"
    "                                 [--ready P] [--valid P] [--seed S]\n"
    "Renders like 'pluecker render --test fixed' (same options and defaults, see\n"
    "'pluecker render --help'), through the model's batched traversal with --pool rays\n"
    "in flight; every batch of box queries is spread over the array's lanes round-robin,\n"
    "all lanes streaming at once, and each answer is compared with the golden model.\n"
    "--test may only be fixed; --mode, --coord-bits and --dir-bits default to (and must\n"
    "match) the build.\n"
    "  --out FILE     PNG image                                        [render.png]\n"
    "  --stats FILE   the statistics of 'pluecker render' plus an \"rtl\" section (with\n"
    "                 the lanes' counts)\n"
    "  --ready P      each lane's out_ready_i high with probability P a cycle        [1]\n"
    "  --valid P      a lane with a query waiting offers it with probability P       [1]\n"
    "  --seed S       seed of those draws                                            [1]\n"
    "  --quiet        no progress on stderr\n"
    "exit status: 0 ok, 1 mismatch or RTL protocol error, 2 bad input or options\n";

struct StreamOptions {
    double ready = 1.0, valid = 1.0;
    std::uint64_t seed = 1;
};

// --ready, --valid and --seed, taken out of the render's command line.
StreamOptions stream_options(std::vector<std::string>& argv) {
    std::vector<std::string> own;
    for (const char* name : {"ready", "valid", "seed"})
        if (const auto v = take_option(argv, name)) own.insert(own.end(), {std::string("--") + name, *v});
    const app::Args a(own, {"ready", "valid", "seed"}, {});
    StreamOptions o;
    o.ready = probability(a, "ready", 1.0);
    o.valid = probability(a, "valid", 1.0);
    o.seed = static_cast<std::uint64_t>(a.get_int("seed", 1, 0, 0x7fffffffffffffffl));
    return o;
}

}  // namespace

int cmd_render(const std::vector<std::string>& given) {
    std::vector<std::string> argv = given;
    const StreamOptions so = stream_options(argv);
    // The build's configuration fills in what the command line leaves out.
    const FixedFormat built = built_format();
    const std::optional<app::Args> a = render_args(argv, kUsage, "fixed", check_build_options,
                                                   {{"coord-bits", std::to_string(built.coord_bits)},
                                                    {"dir-bits", std::to_string(built.dir_bits)},
                                                    {"mode", mode_name(built.mode)}});
    if (!a) return 0;
    const auto s = batched_setup(*a);

    ArrayRtl rtl;
    configure_stream(rtl, so.ready, so.valid, so.seed);
    RtlBoxEngine<BoxQuery, ArrayRtl, LaneQuery> engine(
        rtl, [](const BoxQuery& q) { return pack_lane_query(q.ray, q.box); },
        [built](const BoxQuery& q) { return fixed_hit(q.ray, q.box, built); });
    RenderStats st;
    const StreamStats& rs = rtl.stats();
    const double seconds = render_through(*s, *a, engine, st, [&](double wall) {
        nlohmann::json j = rtl_section("pluecker_sim_array", engine.queries(), engine.batches(),
                                       engine.mismatches(), engine.rtl_seconds(), rs, wall);
        j["units"] = {{"dsp", SIM_ARRAY_DSP}, {"lut", SIM_ARRAY_LUT}, {"rom", SIM_ARRAY_ROM}};
        j["pipeline"] = SIM_PIPELINE;
        j["lanes"] = lanes_json(rtl);
        return j;
    });
    std::printf("render %s %dx%d (array %s, order %s, build %s): %llu box queries in %llu batches through "
                "%d lanes, %llu cycles (%.2f queries a cycle), %.3f M queries/s in the RTL loop, %.2f s in all, "
                "%llu mismatches\n",
                s->mesh.name.c_str(), s->opts.width, s->opts.height, build_name().c_str(), order_name(s->opts.order),
                method_name(s->build), static_cast<unsigned long long>(engine.queries()),
                static_cast<unsigned long long>(engine.batches()), kLanes,
                static_cast<unsigned long long>(rs.cycles),
                rs.cycles ? static_cast<double>(engine.queries()) / static_cast<double>(rs.cycles) : 0.0,
                engine.queries_per_second() / 1e6, seconds, static_cast<unsigned long long>(engine.mismatches()));
    return engine.mismatches() == 0 ? 0 : 1;
}

}  // namespace pluecker::sim
