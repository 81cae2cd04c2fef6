// SPDX-License-Identifier: MIT
// `pluecker plan`: the narrowest fixed-point widths whose extra traversal
// work on a scene stays within a bound, as RTL parameters and make
// variables, with the hardware cost measured by `make synth` (when measured).
#include "commands.hpp"
#include "pluecker/app/names.hpp"
#include "pluecker/app/render_options.hpp"
#include "study_cli.hpp"

#include "pluecker/study.hpp"

#include <nlohmann/json.hpp>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <sstream>

namespace pluecker::cli {

namespace {

constexpr const char* kUsage =
    "usage: pluecker plan --scene S --max-extra-work P [options]\n"
    "Measures, for increasing widths, the extra box tests of a conservative\n"
    "fixed-point render over the exact reference (pluecker/study.hpp) and stops at\n"
    "the first width pair with extra work <= P percent. Prints it as RTL parameters\n"
    "and make variables, and its hardware cost from out/synth/<C>x<D>/summary.json\n"
    "(`make synth`) when that has been measured.\n"
    "With --local K-list, also the narrowest local-frame box width K (pluecker/local.hpp)\n"
    "within P over the local path's exact reference, and a choice between the two:\n"
    "the unit with more effective box tests per second per chip (box tests per\n"
    "second per chip at speed grade 8 from the synthesis summaries, divided by\n"
    "1 + extra work); when either is not synthesised yet, the plan says so and\n"
    "keeps the global unit.\n"
    "exit status: 0 a width found, 1 none of --widths (nor --local) meets P, 2 bad input\n";

std::string pair_str(const WidthPair& w) { return std::to_string(w.coord_bits) + "x" + std::to_string(w.dir_bits); }

std::string make_vars(const WidthPair& w) {
    return "COORD_BITS=" + std::to_string(w.coord_bits) + " DIR_BITS=" + std::to_string(w.dir_bits);
}

std::optional<nlohmann::json> read_json(const std::filesystem::path& p) {
    std::ifstream f(p);
    if (!f) return std::nullopt;
    try {
        return nlohmann::json::parse(f);
    } catch (const nlohmann::json::exception&) {
        return std::nullopt;
    }
}

long get_long(const nlohmann::json& j, const char* key) {
    return j.contains(key) && j[key].is_number() ? j[key].get<long>() : -1;
}

// Device capacity as the place-and-route reports of this width state it
// (nextpnr's report, "utilization" -> available), when one exists.
std::optional<nlohmann::json> device_capacity(const std::filesystem::path& dir) {
    std::error_code ec;
    for (const auto& e : std::filesystem::directory_iterator(dir / "pnr", ec)) {
        const auto rep = read_json(e.path() / "report.json");
        if (rep && rep->contains("utilization")) return (*rep)["utilization"];
    }
    return std::nullopt;
}

std::string local_str(const LocalSpec& sp) {
    return "K=" + std::to_string(sp.format.box_bits) + " D=" + std::to_string(sp.format.dir_bits) +
           " G=" + std::to_string(sp.format.grid_bits);
}

std::string local_make_vars(const LocalSpec& sp, int children) {
    return "UNIT=local BOX_BITS=" + std::to_string(sp.format.box_bits) + " LOCAL_DIR_BITS=" +
           std::to_string(sp.format.dir_bits) + " GRID_BITS=" + std::to_string(sp.format.grid_bits) +
           " CHILDREN=" + std::to_string(children);
}

// The folder `make synth-local` writes for the local unit (scripts/synth.py).
std::string local_synth_name(const LocalSpec& sp, int children) {
    return "local_k" + std::to_string(sp.format.box_bits) + "_d" + std::to_string(sp.format.dir_bits) + "_g" +
           std::to_string(sp.format.grid_bits) + "_c" + std::to_string(children);
}

// Box tests per second per chip at speed grade 8 from a synthesis summary
// (scripts/synth.py: units per LFE5U-85F x box tests per clock x median Fmax).
std::optional<double> chip_rate(const std::filesystem::path& summary) {
    const auto sum = read_json(summary);
    if (!sum || !sum->contains("box_tests_per_s_per_chip")) return std::nullopt;
    const nlohmann::json& r = (*sum)["box_tests_per_s_per_chip"];
    if (!r.contains("8") || !r["8"].is_number()) return std::nullopt;
    return r["8"].get<double>();
}

void print_hardware(const std::filesystem::path& synth_dir, const WidthPair& w, std::ostream& os) {
    const std::filesystem::path dir = synth_dir / pair_str(w);
    const auto sum = read_json(dir / "summary.json");
    if (!sum) {
        os << "hardware cost: not measured yet (no " << (dir / "summary.json").string() << ")\n"
           << "  measure it with: make synth " << make_vars(w) << "\n";
        return;
    }
    os << "hardware cost (" << (dir / "summary.json").string() << ", " << sum->value("device", "?") << ", "
       << (sum->value("out_of_context", false) ? "out of context" : "in context") << "):\n";
    const nlohmann::json u = sum->value("utilisation", nlohmann::json::object());
    os << "  LUT4 " << get_long(u, "LUT4") << ", CCU2C " << get_long(u, "CCU2C") << ", FF "
       << get_long(u, "TRELLIS_FF") << " (unit " << get_long(u, "dut_ff") << ", harness " << get_long(u, "harness_ff")
       << "), MULT18X18D " << get_long(u, "MULT18X18D");
    if (u.contains("placed") && u["placed"].contains("TRELLIS_COMB"))
        os << ", placed TRELLIS_COMB (LUT4 slots) " << u["placed"]["TRELLIS_COMB"].get<long>();
    os << "\n";
    const auto lat = sum->find("latency");
    os << "  latency: " << (lat != sum->end() && lat->is_number() ? std::to_string(lat->get<long>()) + " cycles"
                                                                  : std::string("unknown"))
       << ", one box test per clock\n";
    const nlohmann::json fm = sum->value("fmax_mhz", nlohmann::json::object());
    if (fm.empty()) {
        os << "  Fmax: not measured (synthesis without place and route); run: make synth " << make_vars(w) << "\n";
    } else {
        for (const auto& [speed, f] : fm.items()) {
            char line[160];
            std::snprintf(line, sizeof line, "  Fmax speed grade %s: median %.1f MHz [%.1f-%.1f] over %ld seeds\n",
                          speed.c_str(), f.value("median", 0.0), f.value("min", 0.0), f.value("max", 0.0),
                          f.value("seeds", 0L));
            os << line;
        }
    }
    const auto cap = device_capacity(dir);
    const long mult = get_long(u, "MULT18X18D");
    long comb = -1;
    if (u.contains("placed") && u["placed"].contains("TRELLIS_COMB")) comb = u["placed"]["TRELLIS_COMB"].get<long>();
    if (cap && comb > 0 && cap->contains("MULT18X18D") && cap->contains("TRELLIS_COMB")) {
        const long mult_av = (*cap)["MULT18X18D"].value("available", 0L);
        const long comb_av = (*cap)["TRELLIS_COMB"].value("available", 0L);
        const long by_comb = comb_av / comb;
        os << "  units per device (upper bound, no routing margin): ";
        if (mult > 0) {
            const long by_mult = mult_av / mult;
            os << std::min(by_mult, by_comb) << " (MULT18X18D " << mult_av << "/" << mult << " = " << by_mult << ", ";
        } else {
            os << by_comb << " (fabric multipliers, no MULT18X18D; ";
        }
        os << "LUT4 slots " << comb_av << "/" << comb << " = " << by_comb << "; capacities from nextpnr's report)\n";
    }
}

void print_steps(const SceneSetup& s, const PlanResult& r, const std::optional<LocalPlanResult>& lr,
                 std::ostream& os) {
    std::uint64_t rays = 0;
    for (const auto n : r.reference.stats.rays) rays += n;
    os << "scene " << s.mesh.name << ", " << s.opts.width << "x" << s.opts.height << ", order "
       << order_name(s.opts.order) << ": exact reference " << r.reference.stats.traversal.box_tests
       << " box tests for " << rays << " rays\n";
    char line[200];
    for (const PlanStep& st : r.steps) {
        std::snprintf(line, sizeof line, "  %-6s extra box tests %8.3f%%  (%llu box tests)\n",
                      pair_str(st.widths).c_str(), st.extra_box_tests_percent,
                      static_cast<unsigned long long>(st.work.stats.traversal.box_tests));
        os << line;
    }
    if (!lr) return;
    os << "local frames: exact reference on the local path " << lr->reference.stats.traversal.box_tests
       << " box tests\n";
    for (const LocalPlanStep& st : lr->steps) {
        std::snprintf(line, sizeof line, "  %-14s extra box tests %8.3f%%  (%llu box tests)\n",
                      local_str(st.spec).c_str(), st.extra_box_tests_percent,
                      static_cast<unsigned long long>(st.work.stats.traversal.box_tests));
        os << line;
    }
}

// Global or local, when both meet the bound: the larger effective box
// tests per second per chip (chip_rate / (1 + extra work)); the global unit
// when either has no synthesis summary yet (said so, with the commands).
bool choose_local(const PlanResult& r, const LocalPlanResult& lr, int children,
                  const std::filesystem::path& synth_dir, std::ostream& os) {
    if (!r.chosen) {
        os << "global: no width pair within the bound; local frames chosen\n";
        return true;
    }
    const PlanStep& g = r.steps[*r.chosen];
    const LocalPlanStep& l = lr.steps[*lr.chosen];
    const auto g_rate = chip_rate(synth_dir / pair_str(g.widths) / "summary.json");
    const auto l_rate = chip_rate(synth_dir / local_synth_name(l.spec, children) / "summary.json");
    if (!g_rate || !l_rate) {
        os << "global " << pair_str(g.widths) << " or local " << local_str(l.spec)
           << ": the choice needs both units' box tests per second per chip; not synthesised yet:";
        if (!g_rate) os << " make synth " << make_vars(g.widths) << ";";
        if (!l_rate) os << " make synth " << local_make_vars(l.spec, children) << ";";
        os << " until then the plan keeps the global unit\n";
        return false;
    }
    const double ge = *g_rate / (1.0 + g.extra_box_tests_percent / 100.0);
    const double le = *l_rate / (1.0 + l.extra_box_tests_percent / 100.0);
    char line[300];
    std::snprintf(line, sizeof line,
                  "effective box tests per second per chip (speed 8, / (1 + extra work)): global %s %.3g, "
                  "local %s (%d children a query) %.3g\n",
                  pair_str(g.widths).c_str(), ge, local_str(l.spec).c_str(), children, le);
    os << line;
    return le > ge;
}

void print_local_choice(const LocalPlanStep& c, int children, double p, const std::filesystem::path& synth_dir,
                        std::ostream& os) {
    const LocalFormat& f = c.spec.format;
    char line[200];
    std::snprintf(line, sizeof line, "chosen: local frames %s (extra box tests %.3f%% <= %g%%)\n",
                  local_str(c.spec).c_str(), c.extra_box_tests_percent, p);
    os << line;
    os << "RTL parameters: pluecker_local_intersector #(.BOX_BITS(" << f.box_bits << "), .DIR_BITS(" << f.dir_bits
       << "), .GRID_BITS(" << f.grid_bits << "), .CHILDREN(" << children << "))\n";
    os << "make variables: " << local_make_vars(c.spec, children) << "\n";
    os << "make synth " << local_make_vars(c.spec, children) << "\n";
    const std::filesystem::path summary = synth_dir / local_synth_name(c.spec, children) / "summary.json";
    if (const auto rate = chip_rate(summary))
        os << "hardware cost: " << summary.string() << " (box tests per second per chip at speed 8: " << *rate
           << ")\n";
    else
        os << "hardware cost: not measured yet (no " << summary.string() << ")\n";
}

}  // namespace

int cmd_plan(const std::vector<std::string>& argv) {
    std::set<std::string> options = study_scene_options();
    options.insert({"max-extra-work", "widths", "synth-dir", "out", "local", "local-dir-bits", "grid-bits", "frames",
                    "cells", "children"});
    const Args a(with_default_size(argv, kStudyDefaultSize), options, {"help", "quiet"});
    if (a.has("help")) {
        std::printf("%s%s%s", kUsage, study_scene_help(), mesh_formats_help().c_str());
        std::printf(
            "  --max-extra-work P   bound on extra box tests, percent (>= 0)      [required]\n"
            "  --widths SPEC    candidates in order: A:B[:S] | W,.. | CxD,..       [6:24]\n"
            "  --synth-dir DIR  where `make synth` writes <C>x<D>/summary.json   [out/synth]\n"
            "  --out FILE       also write the plan as make variables (COORD_BITS := ..,\n"
            "                   or UNIT := local, BOX_BITS := .. when local is chosen),\n"
            "                   for `make synth PLAN=FILE`\n"
            "  --local SPEC     local-frame box widths K too: A:B[:S] | K,K,.. (4..16)  [none]\n"
            "  --local-dir-bits D, --grid-bits G, --frames, --cells: as in `pluecker study`\n"
            "  --children C     children per query of the local unit (1 or 2)       [2]\n"
            "  --quiet          no progress on stderr\n");
        return 0;
    }
    if (!a.positional().empty()) throw InputError("unexpected argument '" + a.positional().front() + "'");
    if (!a.has("max-extra-work")) throw InputError("option --max-extra-work is required (percent, >= 0)");
    const double p = a.get_double("max-extra-work", 0.0);
    check_max_extra_work(p);
    const std::vector<WidthPair> widths = parse_widths(a.get("widths", "6:24"));
    const std::string synth_dir = a.get("synth-dir", "out/synth");
    const bool quiet = a.has("quiet");
    const auto s = make_study_setup(a);
    if (!quiet)
        std::fprintf(stderr, "plan: %s, %zu triangles, %s build, order %s, %dx%d, max extra work %g%%\n",
                     s->mesh.name.c_str(), s->mesh.triangles.size(), method_name(s->build),
                     order_name(s->opts.order), s->opts.width, s->opts.height, p);
    const std::vector<LocalSpec> local = parse_local_specs(a);
    if (a.has("children") && local.empty()) throw InputError("option --children needs --local");
    const int children = static_cast<int>(a.get_int("children", 2, 1, 2));
    const PlanResult r = plan_widths(s->mesh, s->bvh, s->opts, widths, p, [&](const PlanStep& st) {
        if (!quiet)
            std::fprintf(stderr, "plan: %s: extra box tests %.3f%%\n", pair_str(st.widths).c_str(),
                         st.extra_box_tests_percent);
    });
    std::optional<LocalPlanResult> lr;
    if (!local.empty())
        lr = plan_local(s->mesh, s->bvh, s->opts, local, p, [&](const LocalPlanStep& st) {
            if (!quiet)
                std::fprintf(stderr, "plan: local %s: extra box tests %.3f%%\n", local_str(st.spec).c_str(),
                             st.extra_box_tests_percent);
        });
    std::ostringstream os;
    print_steps(*s, r, lr, os);
    if (!r.chosen && !(lr && lr->chosen)) {
        os << "no width of --widths" << (lr ? " nor of --local" : "") << " keeps the extra box tests within " << p
           << "%\n";
        std::cout << os.str();
        return 1;
    }
    const bool use_local = lr && lr->chosen && choose_local(r, *lr, children, synth_dir, os);
    std::string plan_vars;
    double extra = 0;
    if (use_local) {
        const LocalPlanStep& c = lr->steps[*lr->chosen];
        extra = c.extra_box_tests_percent;
        print_local_choice(c, children, p, synth_dir, os);
        plan_vars = "UNIT := local\nBOX_BITS := " + std::to_string(c.spec.format.box_bits) +
                    "\nLOCAL_DIR_BITS := " + std::to_string(c.spec.format.dir_bits) +
                    "\nGRID_BITS := " + std::to_string(c.spec.format.grid_bits) +
                    "\nCHILDREN := " + std::to_string(children) + "\n";
    } else {
        const PlanStep& c = r.steps[*r.chosen];
        const WidthPair w = c.widths;
        extra = c.extra_box_tests_percent;
        char line[200];
        std::snprintf(line, sizeof line, "chosen: COORD_BITS=%d DIR_BITS=%d (extra box tests %.3f%% <= %g%%)\n",
                      w.coord_bits, w.dir_bits, c.extra_box_tests_percent, p);
        os << line;
        os << "RTL parameters: pluecker_intersector #(.COORD_BITS(" << w.coord_bits << "), .DIR_BITS(" << w.dir_bits
           << "))\n";
        os << "make variables: " << make_vars(w) << "\n";
        os << "make synth " << make_vars(w) << "\n";
        print_hardware(synth_dir, w, os);
        plan_vars = "COORD_BITS := " + std::to_string(w.coord_bits) + "\nDIR_BITS := " + std::to_string(w.dir_bits) + "\n";
    }
    std::cout << os.str();
    if (a.has("out")) {
        const std::string path = a.get("out", "");
        std::ofstream f(path);
        if (!f) throw InputError("option --out: cannot write '" + path + "'");
        char line[200];
        std::snprintf(line, sizeof line,
                      "# pluecker plan: %s %dx%d order %s, max extra work %g%%: extra box tests %.3f%%\n",
                      s->mesh.name.c_str(), s->opts.width, s->opts.height, order_name(s->opts.order), p, extra);
        f << line << plan_vars;
        if (!f) throw InputError("option --out: cannot write '" + path + "'");
        if (!quiet) std::fprintf(stderr, "plan: wrote %s (use: make synth PLAN=%s)\n", path.c_str(), path.c_str());
    }
    return 0;
}

}  // namespace pluecker::cli
