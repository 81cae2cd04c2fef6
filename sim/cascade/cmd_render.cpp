// SPDX-License-Identifier: MIT
// `pluecker_sim_cascade render`: the render of `pluecker cascade` with
// every box query answered by the cascade (hardware in the loop): the
// traversal runs on the wide format (as run_cascade sets it up), each batch
// is set up in both formats and spread over the narrow lanes round-robin,
// and each answer is checked against the golden model's cascade_answer.
#include "cascade_engine.hpp"
#include "commands.hpp"
#include "hil_render.hpp"

#include "pluecker/app/names.hpp"
#include "pluecker/image.hpp"

#include <cerrno>
#include <chrono>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <optional>
#include <set>

namespace pluecker::sim {
namespace {

constexpr const char* kUsage =
    "usage: pluecker_sim_cascade render [scene options of 'pluecker cascade'] [--narrow CxD] [--wide CxD]\n"
    "                                   [--out IMG.png] [--stats STATS.json] [--no-check]\n"
    "                                   [--ready P] [--valid P] [--seed S]\n"
    "Renders as 'pluecker cascade' does (same scene options and defaults, --size 128;\n"
    "see 'pluecker cascade --help'): the batched traversal on the wide format with every\n"
    "box query answered by the cascade. Each query is set up in both formats by the model\n"
    "(a ray that never meets a format's range cube is a miss without an RTL query), the\n"
    "queries of a batch are spread over the narrow lanes round-robin, all lanes streaming\n"
    "at once, and each answer is compared with the model's: a certain answer must be the\n"
    "narrow answer of a query the model is sure about, an escalated one the wide test of\n"
    "a query the model finds uncertain.\n"
    "  --narrow CxD   must match the build's narrow widths              [the build's]\n"
    "  --wide CxD     must match the build's wide widths                [the build's]\n"
    "  --out FILE     PNG image                                         [render.png]\n"
    "  --stats FILE   the statistics of 'pluecker render', a \"cascade\" section with the\n"
    "                 answers in the form of 'pluecker cascade --json' (\"answers\": the\n"
    "                 RTL's, \"model_answers\": the model's) and an \"rtl\" section\n"
    "  --no-check     do not compare every answer with the exact test as well\n"
    "  --ready P      each lane's out_ready_i and esc_ready_i high with probability P  [1]\n"
    "  --valid P      a lane with a query waiting offers it with probability P         [1]\n"
    "  --seed S       seed of those draws                                              [1]\n"
    "  --quiet        no progress on stderr\n"
    "exit status: 0 ok, 1 mismatch or RTL protocol error, 2 bad input or options\n";

// `pluecker cascade`'s default image size.
constexpr const char* kDefaultSize = "128";

std::set<std::string> render_options() {
    std::set<std::string> o = app::kSceneOptions;
    for (const char* f : {"test", "coord-bits", "dir-bits", "mode", "pool", "box-bits", "grid-bits", "frames", "cells"})
        o.erase(f);
    o.insert({"narrow", "wide", "stats", "ready", "valid", "seed"});
    return o;
}

const std::set<std::string> kSwitches = {"help", "quiet", "no-check"};

// The command line completed with the cascade's traversal format (the wide
// one, conservative) and the default size; nullopt after --help.
std::optional<app::Args> render_args(const std::vector<std::string>& argv) {
    const std::set<std::string> options = render_options();
    const app::Args given(argv, options, kSwitches);
    if (given.has("help")) {
        std::fputs(kUsage, stdout);
        return std::nullopt;
    }
    if (!given.positional().empty()) throw InputError("unexpected argument '" + given.positional().front() + "'");
    if (given.has("threads")) throw InputError("option --threads: the hardware-in-the-loop render runs on one thread");
    check_build_widths(given);
    const FixedFormat wide = built_formats().wide;
    std::vector<std::string> full = argv;
    if (!given.has("size")) full.insert(full.end(), {"--size", kDefaultSize});
    full.insert(full.end(), {"--test", "fixed", "--coord-bits", std::to_string(wide.coord_bits), "--dir-bits",
                             std::to_string(wide.dir_bits), "--mode", mode_name(wide.mode)});
    std::set<std::string> all = options;
    all.insert({"test", "coord-bits", "dir-bits", "mode"});
    return app::Args(full, all, kSwitches);
}

nlohmann::json cascade_json(const CascadeRtlEngine& engine) {
    const CascadeFormats f = built_formats();
    return {{"narrow", {{"coord_bits", f.narrow.coord_bits}, {"dir_bits", f.narrow.dir_bits}}},
            {"wide", {{"coord_bits", f.wide.coord_bits}, {"dir_bits", f.wide.dir_bits}}},
            {"lanes", kLanes},
            {"answers", cascade_counts_json(engine.rtl_counts())},
            {"model_answers", cascade_counts_json(engine.model_counts())},
            {"missed_range", engine.missed()},
            {"mismatches", engine.mismatches()}};
}

nlohmann::json rtl_json(const CascadeRtl& rtl, const CascadeRtlEngine& engine, double wall) {
    nlohmann::json j = rtl_section("pluecker_sim_cascade", engine.rtl_queries(), engine.batches(),
                                   engine.mismatches(), engine.rtl_seconds(), rtl.stats(), wall);
    j["pipeline"] = SIM_PIPELINE;
    j["escalated"] = rtl.escalated();
    j["esc_stall_cycles"] = rtl.esc_stall_cycles();
    j["lanes"] = lanes_json(rtl);
    return j;
}

void write_json(const std::string& path, const nlohmann::json& j) {
    std::ofstream f(path);
    if (!f) throw InputError("option --stats: cannot write '" + path + "' (" + std::strerror(errno) + ")");
    f << j.dump(2) << "\n";
    if (!f) throw InputError("option --stats: cannot write '" + path + "'");
}

void print_summary(const app::SceneSetup& s, const CascadeRtl& rtl, const CascadeRtlEngine& engine, double seconds) {
    const CascadeCounts& c = engine.rtl_counts();
    const StreamStats& rs = rtl.stats();
    std::printf("render %s %dx%d (cascade %s, order %s, build %s): %llu box queries in %llu batches, %llu through "
                "the cascade (%llu missed a range cube), %llu escalated (%.3f %%), %llu cycles (%.2f queries a "
                "cycle), %.3f M queries/s in the RTL loop, %.2f s in all, %llu mismatches\n",
                s.mesh.name.c_str(), s.opts.width, s.opts.height, build_name().c_str(), order_name(s.opts.order),
                method_name(s.build), static_cast<unsigned long long>(c.queries),
                static_cast<unsigned long long>(engine.batches()),
                static_cast<unsigned long long>(engine.rtl_queries()),
                static_cast<unsigned long long>(engine.missed()), static_cast<unsigned long long>(c.escalated),
                100.0 * c.escalated_fraction(), static_cast<unsigned long long>(rs.cycles),
                rs.cycles ? static_cast<double>(engine.rtl_queries()) / static_cast<double>(rs.cycles) : 0.0,
                engine.rtl_seconds() > 0 ? static_cast<double>(engine.rtl_queries()) / engine.rtl_seconds() / 1e6
                                         : 0.0,
                seconds, static_cast<unsigned long long>(engine.mismatches()));
}

}  // namespace

int cmd_render(const std::vector<std::string>& argv) {
    const std::optional<app::Args> a = render_args(argv);
    if (!a) return 0;
    const double ready = probability(*a, "ready", 1.0);
    const double valid = probability(*a, "valid", 1.0);
    const auto seed = static_cast<std::uint64_t>(a->get_int("seed", 1, 0, 0x7fffffffffffffffl));
    const auto s = batched_setup(*a);

    CascadeRtl rtl;
    configure_stream(rtl, ready, valid, seed);
    CascadeRtlEngine engine(rtl, s->bvh, !a->has("no-check"));
    RenderStats st;
    const auto t0 = std::chrono::steady_clock::now();
    const Image img = render_batched(*s->scene, s->opts, engine, st);
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    write_png(img, a->get("out", "render.png"));
    if (a->has("stats")) {
        nlohmann::json j = stats_json(*s, st);
        j["cascade"] = cascade_json(engine);
        j["rtl"] = rtl_json(rtl, engine, seconds);
        write_json(a->get("stats", ""), j);
    }
    print_summary(*s, rtl, engine, seconds);
    return engine.mismatches() == 0 ? 0 : 1;
}

}  // namespace pluecker::sim
