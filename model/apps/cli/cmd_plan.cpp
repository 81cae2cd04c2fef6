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
    "exit status: 0 a width found, 1 none of --widths meets P, 2 bad input\n";

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

}  // namespace

int cmd_plan(const std::vector<std::string>& argv) {
    std::set<std::string> options = study_scene_options();
    options.insert({"max-extra-work", "widths", "synth-dir", "out"});
    const Args a(with_default_size(argv, kStudyDefaultSize), options, {"help", "quiet"});
    if (a.has("help")) {
        std::printf("%s%s", kUsage, study_scene_help());
        std::printf(
            "  --max-extra-work P   bound on extra box tests, percent (>= 0)      [required]\n"
            "  --widths SPEC    candidates in order: A:B[:S] | W,.. | CxD,..       [6:24]\n"
            "  --synth-dir DIR  where `make synth` writes <C>x<D>/summary.json   [out/synth]\n"
            "  --out FILE       also write the plan as make variables (COORD_BITS := ..),\n"
            "                   for `make synth PLAN=FILE`\n"
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
    const PlanResult r = plan_widths(s->mesh, s->bvh, s->opts, widths, p, [&](const PlanStep& st) {
        if (!quiet)
            std::fprintf(stderr, "plan: %s: extra box tests %.3f%%\n", pair_str(st.widths).c_str(),
                         st.extra_box_tests_percent);
    });
    std::ostringstream os;
    std::uint64_t rays = 0;
    for (const auto n : r.reference.stats.rays) rays += n;
    os << "scene " << s->mesh.name << ", " << s->opts.width << "x" << s->opts.height << ", order "
       << order_name(s->opts.order) << ": exact reference " << r.reference.stats.traversal.box_tests
       << " box tests for " << rays << " rays\n";
    for (const PlanStep& st : r.steps) {
        char line[160];
        std::snprintf(line, sizeof line, "  %-6s extra box tests %8.3f%%  (%llu box tests)\n",
                      pair_str(st.widths).c_str(), st.extra_box_tests_percent,
                      static_cast<unsigned long long>(st.work.stats.traversal.box_tests));
        os << line;
    }
    if (!r.chosen) {
        os << "no width pair of --widths keeps the extra box tests within " << p << "%\n";
        std::cout << os.str();
        return 1;
    }
    const PlanStep& c = r.steps[*r.chosen];
    const WidthPair w = c.widths;
    char line[200];
    std::snprintf(line, sizeof line, "chosen: COORD_BITS=%d DIR_BITS=%d (extra box tests %.3f%% <= %g%%)\n",
                  w.coord_bits, w.dir_bits, c.extra_box_tests_percent, p);
    os << line;
    os << "RTL parameters: pluecker_intersector #(.COORD_BITS(" << w.coord_bits << "), .DIR_BITS(" << w.dir_bits
       << "))\n";
    os << "make variables: " << make_vars(w) << "\n";
    os << "make synth " << make_vars(w) << "\n";
    print_hardware(synth_dir, w, os);
    std::cout << os.str();
    if (a.has("out")) {
        const std::string path = a.get("out", "");
        std::ofstream f(path);
        if (!f) throw InputError("option --out: cannot write '" + path + "'");
        std::snprintf(line, sizeof line,
                      "# pluecker plan: %s %dx%d order %s, max extra work %g%%: extra box tests %.3f%%\n",
                      s->mesh.name.c_str(), s->opts.width, s->opts.height, order_name(s->opts.order), p,
                      c.extra_box_tests_percent);
        f << line << "COORD_BITS := " << w.coord_bits << "\nDIR_BITS := " << w.dir_bits << "\n";
        if (!f) throw InputError("option --out: cannot write '" + path + "'");
        if (!quiet) std::fprintf(stderr, "plan: wrote %s (use: make synth PLAN=%s)\n", path.c_str(), path.c_str());
    }
    return 0;
}

}  // namespace pluecker::cli
