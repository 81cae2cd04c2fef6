// SPDX-License-Identifier: MIT
// Shared by `pluecker study` and `pluecker plan`: the scene options (those of
// render_setup.hpp without the box test and format, which the study sets per
// run), a smaller default size, and the summary table.
#pragma once

#include "commands.hpp"
#include "pluecker/app/names.hpp"
#include "pluecker/app/render_options.hpp"

#include "pluecker/study.hpp"

#include <cstdio>
#include <fstream>
#include <iostream>
#include <ostream>
#include <set>
#include <string>
#include <vector>

namespace pluecker::cli {

inline constexpr int kStudyDefaultSize = 128;

inline std::set<std::string> study_scene_options() {
    std::set<std::string> o = kSceneOptions;
    for (const char* f : {"test", "coord-bits", "dir-bits", "mode", "out", "pool", "box-bits", "grid-bits", "frames",
                          "cells"})
        o.erase(f);
    return o;
}

inline const char* study_scene_help() {
    return "  --scene S        teapot | spheres | sphere:N | FILE (mesh formats below) [teapot]\n"
           "  --order O        fixed | dsa (the fixed-point path's orders)      [dsa]\n"
           "  --build B        median | sah                                     [sah]\n"
           "  --size N         image N x N                                      [128]\n"
           "  --width W --height H   override the size per axis\n"
           "  --epsilon E      BVH box growth                                   [1e-6]\n"
           "  --eye X,Y,Z --look X,Y,Z --up X,Y,Z --fov DEG   camera (default: per scene)\n"
           "  --lights N       1 or 2 point lights                              [2]\n"
           "  --max-depth D    reflection/refraction levels                     [4]\n";
}

// argv with "--size N" appended when no --size is given (make_setup's
// default is the render's 512).
inline std::vector<std::string> with_default_size(std::vector<std::string> argv, int n) {
    for (const std::string& s : argv)
        if (s == "--size" || s.rfind("--size=", 0) == 0) return argv;
    argv.push_back("--size");
    argv.push_back(std::to_string(n));
    return argv;
}

// The scene, BVH and render options; the study sets test and format per run.
inline std::unique_ptr<SceneSetup> make_study_setup(const Args& a) {
    const ChildOrder o = parse_child_order(a.get("order", "dsa"));
    if (o == ChildOrder::Dist) throw InputError("option --order: the fixed-point path takes fixed or dsa, not dist");
    return make_setup(a);
}

// --local K-list with --local-dir-bits, --grid-bits, --frames, --cells
// (empty without --local; the other flags then refused).
inline std::vector<LocalSpec> parse_local_specs(const Args& a) {
    std::vector<LocalSpec> out;
    if (!a.has("local")) {
        for (const char* f : {"local-dir-bits", "grid-bits", "frames", "cells"})
            if (a.has(f)) throw InputError(std::string("option --") + f + " needs --local");
        return out;
    }
    const LocalBuildOptions build = app::parse_local_build(a);
    for (const int k : parse_bit_list(a.get("local", ""), "--local", LocalFormat::kMinBoxBits,
                                      LocalFormat::kMaxBoxBits)) {
        LocalSpec sp;
        sp.format.box_bits = k;
        sp.format.dir_bits = static_cast<int>(a.get_int("local-dir-bits", std::min(k + 3, LocalFormat::kMaxDirBits),
                                                        LocalFormat::kMinDirBits, LocalFormat::kMaxDirBits));
        sp.format.grid_bits = static_cast<int>(a.get_int("grid-bits", sp.format.grid_bits, LocalFormat::kMinBoxBits + 2,
                                                         LocalFormat::kMaxGridBits));
        sp.format.validate();
        sp.build = build;
        out.push_back(sp);
    }
    return out;
}

inline void print_local_table(const StudyResult& r, std::ostream& os) {
    if (!r.local_reference) return;
    char line[256];
    const auto& ref = r.local_reference->stats.traversal;
    os << "local frames (reference on the local path: " << ref.box_tests << " box tests)\n"
       << "  K  D  G   node bits  cons.FM  cons.FHrate  extra box%  extra node%  extra tri%  near.FHrate  "
          "near.wrong_px\n";
    for (const LocalStudy& s : r.local) {
        const auto& t = s.work.stats.traversal;
        std::snprintf(line, sizeof line, "%3d %2d %2d  %10d  %7llu  %11.6f  %10.3f  %11.3f  %10.3f  %11.6f  %13llu\n",
                      s.spec.format.box_bits, s.spec.format.dir_bits, s.spec.format.grid_bits, s.node_bits,
                      static_cast<unsigned long long>(s.conservative.false_misses), s.conservative.false_hit_rate(),
                      extra_percent(t.box_tests, ref.box_tests), extra_percent(t.node_visits, ref.node_visits),
                      extra_percent(t.tri_tests, ref.tri_tests), s.nearest.false_hit_rate(),
                      static_cast<unsigned long long>(s.near.wrong_pixels));
        os << line;
    }
}

// --json FILE: the figures written to FILE, or to stdout for '-'.
inline void write_json_option(const Args& a, const nlohmann::json& j) {
    if (!a.has("json")) return;
    const std::string path = a.get("json", "");
    if (path == "-") {
        std::cout << j.dump(2) << "\n";
        return;
    }
    std::ofstream f(path);
    if (!f) throw InputError("option --json: cannot write '" + path + "'");
    f << j.dump(2) << "\n";
    if (!f) throw InputError("option --json: cannot write '" + path + "'");
}

inline void print_study_table(const StudyResult& r, std::ostream& os) {
    char line[256];
    const auto& ref = r.reference.stats.traversal;
    std::uint64_t rays = 0;
    for (const auto n : r.reference.stats.rays) rays += n;
    std::snprintf(line, sizeof line, "reference (exact answers): %llu rays, %.2f box tests/ray, %.2f node visits/ray, "
                  "%.2f triangle tests/ray\n",
                  static_cast<unsigned long long>(rays), rays ? double(ref.box_tests) / double(rays) : 0.0,
                  rays ? double(ref.node_visits) / double(rays) : 0.0, rays ? double(ref.tri_tests) / double(rays) : 0.0);
    os << line;
    if (r.options.per_query) {
        std::snprintf(line, sizeof line, "float on the same %llu queries: pluecker %llu false misses %llu false hits, "
                      "smits %llu false misses %llu false hits\n",
                      static_cast<unsigned long long>(r.reference.checked.queries),
                      static_cast<unsigned long long>(r.pluecker.false_misses),
                      static_cast<unsigned long long>(r.pluecker.false_hits),
                      static_cast<unsigned long long>(r.smits.false_misses),
                      static_cast<unsigned long long>(r.smits.false_hits));
        os << line;
    }
    os << "  CxD   cons.FM  cons.FHrate  extra box%  extra node%  extra tri%  near.FM(q)  near.FHrate  "
          "near.FM(render)  near.wrong_px\n";
    for (std::size_t k = 0; k < r.options.widths.size(); ++k) {
        const WidthPair w = r.options.widths[k];
        std::string s = std::to_string(w.coord_bits) + "x" + std::to_string(w.dir_bits);
        std::snprintf(line, sizeof line, "%6s", s.c_str());
        os << line;
        if (k < r.queries.size()) {
            std::snprintf(line, sizeof line, "  %7llu  %11.6f",
                          static_cast<unsigned long long>(r.queries[k].conservative.false_misses),
                          r.queries[k].conservative.false_hit_rate());
            os << line;
        } else {
            os << "        -            -";
        }
        if (k < r.work.size()) {
            const auto& t = r.work[k].stats.traversal;
            std::snprintf(line, sizeof line, "  %10.3f  %11.3f  %10.3f", extra_percent(t.box_tests, ref.box_tests),
                          extra_percent(t.node_visits, ref.node_visits), extra_percent(t.tri_tests, ref.tri_tests));
            os << line;
        } else {
            os << "           -            -           -";
        }
        if (k < r.queries.size()) {
            std::snprintf(line, sizeof line, "  %10llu  %11.6f",
                          static_cast<unsigned long long>(r.queries[k].nearest.false_misses),
                          r.queries[k].nearest.false_hit_rate());
            os << line;
        } else {
            os << "           -            -";
        }
        if (k < r.nearest.size()) {
            std::snprintf(line, sizeof line, "  %15llu  %13llu",
                          static_cast<unsigned long long>(r.nearest[k].checked.false_misses),
                          static_cast<unsigned long long>(r.nearest[k].wrong_pixels));
            os << line;
        }
        os << "\n";
    }
}

}  // namespace pluecker::cli
