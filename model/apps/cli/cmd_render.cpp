// SPDX-License-Identifier: MIT
// `pluecker render`: ray trace a scene to PNG, statistics as JSON.
#include "commands.hpp"
#include "pluecker/app/render_options.hpp"

#include "pluecker/image.hpp"
#include "pluecker/render.hpp"

#include <cstdio>
#include <fstream>

namespace pluecker::cli {

namespace {

constexpr const char* kUsage =
    "usage: pluecker render [options]\n"
    "Ray traces a scene (camera, shadow, mirror and glass rays) through the BVH\n"
    "with the chosen box test. --test fixed runs the batched traversal whose box\n"
    "queries a hardware engine could answer (here: the bit-exact model).\n";

}  // namespace

int cmd_render(const std::vector<std::string>& argv) {
    std::set<std::string> options = kSceneOptions;
    options.insert("stats");
    const Args a(argv, options, {"help", "quiet"});
    if (a.has("help")) {
        std::printf("%s%s%s", kUsage, kSceneHelp, mesh_formats_help().c_str());
        std::printf(
            "  --out FILE       PNG image                                        [render.png]\n"
            "  --stats FILE     statistics JSON (rays by kind, node visits, box and\n"
            "                   triangle tests, build and render ms, ...)\n"
            "  --threads T      worker threads (float tests)                     [1]\n"
            "  --pool P         rays in flight (batched tests: fixed, local, f32-*) [256]\n"
            "  --quiet          no progress on stderr\n");
        return 0;
    }
    if (!a.positional().empty()) throw InputError("unexpected argument '" + a.positional().front() + "'");
    const auto s = make_setup(a);
    s->opts.progress = !a.has("quiet");
    const std::string out = a.get("out", "render.png");
    if (!a.has("quiet"))
        std::fprintf(stderr, "render: %s, %zu triangles, %s build %.1f ms, %s, %dx%d\n", s->mesh.name.c_str(),
                     s->mesh.triangles.size(), method_name(s->build), s->bvh.build_ms,
                     config_name(s->opts.test, s->opts.order).c_str(), s->opts.width, s->opts.height);
    RenderStats st;
    const Image img = render(*s->scene, s->opts, st);
    write_png(img, out);
    if (a.has("stats")) {
        const std::string path = a.get("stats", "");
        std::ofstream f(path);
        if (!f) throw InputError("option --stats: cannot write '" + path + "'");
        f << stats_json(*s, st).dump(2) << "\n";
        if (!f) throw InputError("option --stats: cannot write '" + path + "'");
    }
    if (!a.has("quiet"))
        std::fprintf(stderr, "render: %.1f ms, %llu box tests, wrote %s\n", st.render_ms,
                     static_cast<unsigned long long>(st.traversal.box_tests), out.c_str());
    return 0;
}

}  // namespace pluecker::cli
