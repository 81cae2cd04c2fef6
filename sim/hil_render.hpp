// SPDX-License-Identifier: MIT
// The parts of `render` both harnesses share: the command line completed
// with the build's configuration, the batched render through an engine, and
// the image and statistics files (the CLI's statistics plus an "rtl"
// section).
#pragma once

#include "pluecker/app/render_options.hpp"

#include "pluecker/render.hpp"

#include <cerrno>
#include <chrono>
#include <cstring>
#include <fstream>
#include <initializer_list>
#include <string>
#include <utility>
#include <vector>

namespace pluecker::sim {

// argv with `--option value` appended for every default whose option the
// command line (`given`) leaves out.
inline std::vector<std::string> with_defaults(std::vector<std::string> argv, const app::Args& given,
                                              std::initializer_list<std::pair<const char*, std::string>> defaults) {
    for (const auto& [option, value] : defaults)
        if (!given.has(option)) argv.insert(argv.end(), {std::string("--") + option, value});
    return argv;
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
