// SPDX-License-Identifier: MIT
// `pluecker trace`: write the ray/box queries a render's traversal issues.
#include "commands.hpp"
#include "pluecker/app/render_options.hpp"

#include "pluecker/render.hpp"

#include <cstdio>
#include <fstream>
#include <iostream>

namespace pluecker::cli {

namespace {

constexpr const char* kUsage =
    "usage: pluecker trace [options] --out FILE\n"
    "Runs the render's traversal (one thread; pixels in row order, each pixel's\n"
    "rays breadth first) and writes every ray/box query it issues, in order, in\n"
    "the query format (hex floats). For --test fixed the ray is the clipped ray\n"
    "the box test sees.\n";

}  // namespace

int cmd_trace(const std::vector<std::string>& argv) {
    std::set<std::string> options = kSceneOptions;
    options.insert("limit");
    const Args a(argv, options, {"help", "quiet"});
    if (a.has("help")) {
        std::printf("%s%s%s", kUsage, kSceneHelp, mesh_formats_help().c_str());
        std::printf(
            "  --out FILE       query file, '-' for stdout                       [required]\n"
            "  --limit Q        stop after Q queries (0: all)                    [0]\n"
            "  --quiet          no progress on stderr\n");
        return 0;
    }
    if (!a.positional().empty()) throw InputError("unexpected argument '" + a.positional().front() + "'");
    if (!a.has("out")) throw InputError("option --out is required");
    const long limit = a.get_int("limit", 0, 0, std::numeric_limits<long>::max());
    const auto s = make_setup(a);
    s->opts.progress = !a.has("quiet");
    const std::string out = a.get("out", "");
    std::ofstream file;
    std::ostream* os = &std::cout;
    if (out != "-") {
        file.open(out);
        if (!file) throw InputError("option --out: cannot write '" + out + "'");
        os = &file;
    }
    RenderStats st;
    const std::uint64_t n = trace_render(*s->scene, s->opts, *os, static_cast<std::uint64_t>(limit), st);
    os->flush();
    if (!*os) throw InputError("option --out: cannot write '" + out + "'");
    if (!a.has("quiet")) std::fprintf(stderr, "trace: %llu queries\n", static_cast<unsigned long long>(n));
    return 0;
}

}  // namespace pluecker::cli
