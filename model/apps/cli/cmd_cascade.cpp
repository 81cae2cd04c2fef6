// SPDX-License-Identifier: MIT
// `pluecker cascade`: narrow ternary units escalating their uncertain answers
// to a wide unit, measured on a render's traversal queries
// (pluecker/cascade.hpp).
#include "commands.hpp"
#include "pluecker/app/names.hpp"
#include "pluecker/app/render_options.hpp"
#include "study_cli.hpp"

#include "pluecker/cascade.hpp"

#include <cstdio>
#include <iostream>

namespace pluecker::cli {

namespace {

constexpr const char* kUsage =
    "usage: pluecker cascade [options] [--json FILE]\n"
    "Renders the scene with every box query answered by a cascade: a narrow\n"
    "ternary test (certain hit / certain miss / uncertain, ternary.hpp) whose\n"
    "uncertain answers are tested again at the wide width. Per narrow width:\n"
    "the fraction escalated, the certain answers, the extra traversal work of\n"
    "the cascade against exact answers (and of the narrow and wide widths\n"
    "alone), every answer checked against the exact test.\n"
    "Definitions: model/rt/include/pluecker/cascade.hpp (also in the JSON).\n";

void print_table(const CascadeStudyResult& r, std::ostream& os) {
    char line[320];
    const auto ref = r.reference.stats.traversal.box_tests;
    std::snprintf(line, sizeof line, "reference (exact answers): %llu box tests; wide %dx%d",
                  static_cast<unsigned long long>(ref), r.options.wide.coord_bits, r.options.wide.dir_bits);
    os << line;
    if (r.wide_alone)
        std::snprintf(line, sizeof line, " alone: extra box tests %.3f%%\n",
                      extra_percent(r.wide_alone->stats.traversal.box_tests, ref));
    else
        std::snprintf(line, sizeof line, "\n");
    os << line;
    os << "narrow  box tests  escalated%  certain-hit%  certain-miss%  extra box% (cascade)  extra box% (narrow "
          "alone)  false hits  lost hits  false certain  wrong px\n";
    for (const CascadeStudyRow& row : r.rows) {
        const CascadeCounts& c = row.run.counts;
        const double q = c.queries ? double(c.queries) : 1.0;
        const std::string w = std::to_string(row.narrow.coord_bits) + "x" + std::to_string(row.narrow.dir_bits);
        char alone[32] = "-";
        if (row.alone) std::snprintf(alone, sizeof alone, "%.3f", extra_percent(row.alone->stats.traversal.box_tests, ref));
        std::snprintf(line, sizeof line, "%6s  %9llu  %10.3f  %12.3f  %13.3f  %20.3f  %25s  %10llu  %9llu  %13llu  %8llu\n",
                      w.c_str(), static_cast<unsigned long long>(c.queries), 100.0 * c.escalated_fraction(),
                      100.0 * double(c.certain_hits) / q, 100.0 * double(c.certain_misses) / q,
                      extra_percent(row.run.stats.traversal.box_tests, ref), alone,
                      static_cast<unsigned long long>(c.false_hits), static_cast<unsigned long long>(c.false_misses),
                      static_cast<unsigned long long>(c.false_certain_hits),
                      static_cast<unsigned long long>(row.wrong_pixels));
        os << line;
    }
}

}  // namespace

int cmd_cascade(const std::vector<std::string>& argv) {
    std::set<std::string> options = study_scene_options();
    options.insert({"narrow", "wide", "json", "threads"});
    const Args a(with_default_size(argv, kStudyDefaultSize), options, {"help", "quiet", "no-check", "no-alone"});
    if (a.has("help")) {
        std::printf("%s%s", kUsage, study_scene_help());
        std::printf(
            "  --narrow SPEC    narrow widths: A:B[:S] | W,W,.. | CxD,CxD,..    [6:12:2]\n"
            "  --wide CxD       the wide width                                   [16x16]\n"
            "  --json FILE      every figure as JSON ('-' for stdout)\n"
            "  --threads T      renders at once                                  [cores]\n"
            "  --no-check       do not compare every answer with the exact test\n"
            "  --no-alone       skip the renders of the narrow and wide widths alone\n"
            "  --quiet          no progress on stderr\n"
            "(--size defaults to %d here.)\n",
            kStudyDefaultSize);
        std::printf("%s", mesh_formats_help().c_str());
        return 0;
    }
    if (!a.positional().empty()) throw InputError("unexpected argument '" + a.positional().front() + "'");
    CascadeStudyOptions so;
    so.narrow = parse_widths(a.get("narrow", "6:12:2"), "--narrow");
    const std::vector<WidthPair> wide = parse_widths(a.get("wide", "16x16"), "--wide");
    if (wide.size() != 1) throw InputError("option --wide: give one width pair, e.g. 16x16");
    so.wide = wide.front();
    so.threads = static_cast<int>(a.get_int("threads", 0, 0, 1024));
    so.check = !a.has("no-check");
    so.alone = !a.has("no-alone");
    so.progress = !a.has("quiet");
    const auto s = make_study_setup(a);
    so.render = s->opts;
    if (so.progress)
        std::fprintf(stderr, "cascade: %s, %zu triangles, %s build, order %s, %dx%d, %zu narrow widths -> %dx%d\n",
                     s->mesh.name.c_str(), s->mesh.triangles.size(), method_name(s->build),
                     order_name(so.render.order), so.render.width, so.render.height, so.narrow.size(),
                     so.wide.coord_bits, so.wide.dir_bits);
    const CascadeStudyResult r = run_cascade_study(s->mesh, s->bvh, so);
    const nlohmann::json j = cascade_study_json(r, s->mesh, s->bvh, s->build);
    write_json_option(a, j);
    if (a.get("json", "") != "-") print_table(r, std::cout);
    if (so.progress) std::fprintf(stderr, "cascade: done in %.1f s\n", r.seconds);
    // A lost real hit, a false certain hit or a different image is a bug.
    for (const CascadeStudyRow& row : r.rows)
        if (row.run.counts.false_misses || row.run.counts.false_certain_hits || row.wrong_pixels) {
            std::fprintf(stderr, "cascade: error: %dx%d lost real hits or gave false certain hits\n",
                         row.narrow.coord_bits, row.narrow.dir_bits);
            return 1;
        }
    return 0;
}

}  // namespace pluecker::cli
