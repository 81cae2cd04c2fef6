// SPDX-License-Identifier: MIT
// `pluecker study`: what each fixed-point width costs in traversal work and
// accuracy on a render of a scene (pluecker/study.hpp).
#include "commands.hpp"
#include "pluecker/app/names.hpp"
#include "pluecker/app/render_options.hpp"
#include "study_cli.hpp"

#include "pluecker/study.hpp"

#include <cstdio>
#include <fstream>
#include <iostream>

namespace pluecker::cli {

namespace {

constexpr const char* kUsage =
    "usage: pluecker study [options] [--json FILE]\n"
    "Renders the scene (camera and secondary rays) with exact answers to every box\n"
    "query of the fixed-point path (the reference), then per width pair: the\n"
    "per-query false hits/misses of the fixed test (conservative and nearest) and\n"
    "of float pluecker and smits on the reference's queries, the extra traversal\n"
    "work of a conservative render, and the wrong pixels of a nearest render;\n"
    "with --local, the same for local frames (pluecker/local.hpp) against a\n"
    "reference on the local path, with the hierarchy's memory per node.\n"
    "Definitions: model/rt/include/pluecker/study.hpp (also in the JSON).\n";

}  // namespace

int cmd_study(const std::vector<std::string>& argv) {
    std::set<std::string> options = study_scene_options();
    options.insert({"widths", "json", "local", "local-dir-bits", "grid-bits", "frames", "cells"});
    const Args a(with_default_size(argv, kStudyDefaultSize), options,
                 {"help", "quiet", "no-queries", "no-work", "no-nearest", "no-direct"});
    if (a.has("help")) {
        std::printf("%s%s%s", kUsage, study_scene_help(), mesh_formats_help().c_str());
        std::printf(
            "  --widths SPEC    A:B[:S] | W,W,.. | CxD,CxD,..                   [6:24:2]\n"
            "  --local SPEC     local frames too, box widths K: A:B[:S] | K,K,.. (4..16) [none]\n"
            "  --local-dir-bits D   their direction width (4..24)                 [K + 3]\n"
            "  --grid-bits G    their global grid width (K+2..48)                 [32]\n"
            "  --frames parent|own  --cells axis|uniform   their hierarchy      [parent, axis]\n"
            "  --json FILE      every figure as JSON ('-' for stdout)\n"
            "  --threads T      renders at once                                  [cores]\n"
            "  --no-queries --no-work --no-nearest --no-direct   skip a part\n"
            "  --quiet          no progress on stderr\n"
            "(--size defaults to %d here.)\n",
            kStudyDefaultSize);
        return 0;
    }
    if (!a.positional().empty()) throw InputError("unexpected argument '" + a.positional().front() + "'");
    StudyOptions so;
    so.widths = parse_widths(a.get("widths", "6:24:2"));
    so.local = parse_local_specs(a);
    so.threads = static_cast<int>(a.get_int("threads", 0, 0, 1024));
    so.per_query = !a.has("no-queries");
    so.work = !a.has("no-work");
    so.nearest = !a.has("no-nearest");
    so.direct_exact = !a.has("no-direct");
    so.progress = !a.has("quiet");
    const auto s = make_study_setup(a);
    so.render = s->opts;
    if (so.progress)
        std::fprintf(stderr, "study: %s, %zu triangles, %s build, order %s, %dx%d, %zu width pairs\n",
                     s->mesh.name.c_str(), s->mesh.triangles.size(), method_name(s->build),
                     order_name(so.render.order), so.render.width, so.render.height, so.widths.size());
    const StudyResult r = run_study(s->mesh, s->bvh, so);
    const nlohmann::json j = study_json(r, s->mesh, s->bvh, s->build);
    if (a.has("json")) {
        const std::string path = a.get("json", "");
        if (path == "-") {
            std::cout << j.dump(2) << "\n";
        } else {
            std::ofstream f(path);
            if (!f) throw InputError("option --json: cannot write '" + path + "'");
            f << j.dump(2) << "\n";
            if (!f) throw InputError("option --json: cannot write '" + path + "'");
        }
    }
    if (a.get("json", "") != "-") {
        print_study_table(r, std::cout);
        print_local_table(r, std::cout);
    }
    if (so.progress) std::fprintf(stderr, "study: done in %.1f s\n", r.seconds);
    return 0;
}

}  // namespace pluecker::cli
