// SPDX-License-Identifier: MIT
// The parts of `render` both harnesses share: the command line completed
// with the build's configuration, the batched render through an engine, and
// the image and statistics files (the CLI's statistics plus an "rtl"
// section).
#pragma once

#include "pluecker/app/render_options.hpp"

#include "pluecker/render.hpp"

#include "rtl_stream.hpp"

#include <cerrno>
#include <chrono>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <initializer_list>
#include <optional>
#include <set>
#include <string>
#include <utility>
#include <vector>

#ifndef SIM_TAG_BITS
#error "SIM_TAG_BITS must be defined (sim/build.sh passes it)"
#endif

namespace pluecker::sim {

// The command line of a harness's `render`: the options of `pluecker
// render` plus --stats, --help (prints `usage`, returns nullopt) and
// --quiet; no positional argument, --test only `test` (the one the RTL
// answers), no --threads; `check(given)` checks the options that must
// match the build (InputError), and `defaults` (the build's configuration)
// fill in what the command line leaves out.
template <class Check>
std::optional<app::Args> render_args(const std::vector<std::string>& argv, const char* usage, const std::string& test,
                                     Check check,
                                     std::initializer_list<std::pair<const char*, std::string>> defaults) {
    std::set<std::string> options = app::kSceneOptions;
    options.insert("stats");
    const std::set<std::string> switches = {"help", "quiet"};
    const app::Args given(argv, options, switches);
    if (given.has("help")) {
        std::fputs(usage, stdout);
        return std::nullopt;
    }
    if (!given.positional().empty()) throw InputError("unexpected argument '" + given.positional().front() + "'");
    if (given.has("test") && given.get("test", "") != test)
        throw InputError("option --test: this RTL answers the " + test + " test only ('" + given.get("test", "") +
                         "' is not " + test + ")");
    if (given.has("threads")) throw InputError("option --threads: the hardware-in-the-loop render runs on one thread");
    check(given);
    std::vector<std::string> full = argv;
    if (!given.has("test")) full.insert(full.end(), {"--test", test});
    for (const auto& [option, value] : defaults)
        if (!given.has(option)) full.insert(full.end(), {std::string("--") + option, value});
    return app::Args(full, options, switches);
}

// The "rtl" section of a render's statistics, the fields every harness
// reports: `queries` box tests answered by the RTL in `batches` batches,
// `rtl_seconds` of wall time in the RTL loop, `wall` of the whole render.
inline nlohmann::json rtl_section(const char* harness, std::uint64_t queries, std::uint64_t batches,
                                  std::uint64_t mismatches, double rtl_seconds, const StreamStats& rs, double wall) {
    return nlohmann::json{
        {"harness", harness},
        {"tag_bits", SIM_TAG_BITS},
        {"queries", queries},
        {"batches", batches},
        {"mismatches", mismatches},
        {"cycles", rs.cycles},
        {"stall_cycles", rs.stall_cycles},
        {"max_in_flight", rs.max_in_flight},
        {"rtl_seconds", rtl_seconds},
        {"queries_per_second", rtl_seconds > 0 ? static_cast<double>(queries) / rtl_seconds : 0.0},
        {"wall_seconds", wall},
    };
}

// The scene of a batched render (the order must be fixed or dsa).
inline std::unique_ptr<app::SceneSetup> batched_setup(const app::Args& a) {
    auto s = app::make_setup(a);
    if (s->opts.order != ChildOrder::Fixed && s->opts.order != ChildOrder::Dsa)
        throw InputError("option --order: the batched traversal takes fixed or dsa");
    s->opts.progress = !a.has("quiet");
    return s;
}

// Renders through `engine`, writes --out (default render.png) and, with
// --stats, the statistics with the "rtl" section rtl(wall seconds) returns.
// Returns the wall time of the render in seconds.
template <class Engine, class RtlJson>
double render_through(const app::SceneSetup& s, const app::Args& a, Engine& engine, RenderStats& st, RtlJson rtl) {
    const auto t0 = std::chrono::steady_clock::now();
    const Image img = render_batched(*s.scene, s.opts, engine, st);
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    write_png(img, a.get("out", "render.png"));
    if (a.has("stats")) {
        nlohmann::json j = stats_json(*s.scene, s.bvh, s.build, s.opts, st);
        j["rtl"] = rtl(seconds);
        const std::string path = a.get("stats", "");
        std::ofstream f(path);
        if (!f) throw InputError("option --stats: cannot write '" + path + "' (" + std::strerror(errno) + ")");
        f << j.dump(2) << "\n";
        if (!f) throw InputError("option --stats: cannot write '" + path + "'");
    }
    return seconds;
}

}  // namespace pluecker::sim
