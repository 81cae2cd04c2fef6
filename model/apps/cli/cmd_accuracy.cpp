// SPDX-License-Identifier: MIT
// `pluecker accuracy`: every box test against exact_hit on the extreme
// families (and random queries): the host-float tests, the binary32 units'
// models and the fixed-point datapath side by side, per family.
#include "commands.hpp"

#include "pluecker/app/names.hpp"

#include "pluecker/boxtest.hpp"
#include "pluecker/f32unit.hpp"
#include "pluecker/fixed.hpp"
#include "pluecker/querygen.hpp"

#include <cstdio>
#include <functional>
#include <string>
#include <vector>

namespace pluecker::cli {
namespace {

constexpr const char* kUsage =
    "usage: pluecker accuracy [--n N] [--seed S] [--random R] [--widths SPEC] [--families]\n"
    "Answers N extreme queries (querygen's extreme families, default 18000) and R random\n"
    "queries (default 0) with every box test and prints, per test, the real hits, false\n"
    "misses and false hits against exact_hit (exact rational arithmetic on the float\n"
    "inputs):\n"
    "  pluecker, smits               the host-float tests (boxtest.hpp)\n"
    "  f32-pluecker, f32-pluecker-cons, f32-smits\n"
    "                                the binary32 units' models (f32unit.hpp: nearest,\n"
    "                                conservative, slab), bit for bit the RTL's answers\n"
    "  fixed CxD                     the conservative fixed-point datapath at each width\n"
    "                                of --widths (default 16,24; the CLI's --widths syntax)\n"
    "--families adds one line per family and test with false misses or false hits.\n";

struct Test {
    std::string name;
    std::function<bool(const Query&)> hit;
};

struct Tally {
    std::size_t queries = 0, real = 0, false_misses = 0, false_hits = 0;
    void add(bool exact, bool h) {
        ++queries;
        real += exact;
        false_misses += exact && !h;
        false_hits += !exact && h;
    }
};

std::vector<Test> tests(const std::vector<WidthPair>& widths) {
    std::vector<Test> t = {
        {"pluecker", [](const Query& q) { return pluecker_hit(pluecker_setup(q.ray), q.box); }},
        {"smits", [](const Query& q) { return smits_hit(smits_setup(q.ray), q.box); }},
        {"f32-pluecker", [](const Query& q) { return f32_pluecker_hit(q.ray, q.box, false); }},
        {"f32-pluecker-cons", [](const Query& q) { return f32_pluecker_hit(q.ray, q.box, true); }},
        {"f32-smits", [](const Query& q) { return f32_smits_hit(q.ray, q.box); }},
    };
    for (const WidthPair& w : widths) {
        FixedFormat f;
        f.coord_bits = w.coord_bits;
        f.dir_bits = w.dir_bits;
        t.push_back({"fixed " + std::to_string(w.coord_bits) + "x" + std::to_string(w.dir_bits),
                     [f](const Query& q) { return fixed_hit(q.ray, q.box, f); }});
    }
    return t;
}

void print(const char* set, const std::string& name, const Tally& t) {
    std::printf("%-8s %-20s %8zu %8zu %8zu %8zu\n", set, name.c_str(), t.queries, t.real, t.false_misses,
                t.false_hits);
}

}  // namespace

int cmd_accuracy(const std::vector<std::string>& argv) {
    const Args args(argv, {"n", "seed", "random", "widths"}, {"help", "families"});
    if (args.has("help")) {
        std::fputs(kUsage, stdout);
        return 0;
    }
    if (!args.positional().empty()) throw InputError("unexpected argument '" + args.positional()[0] + "'");
    const auto n = static_cast<std::size_t>(args.get_int("n", 18000, 0, 100'000'000));
    const auto r = static_cast<std::size_t>(args.get_int("random", 0, 0, 100'000'000));
    const auto seed = static_cast<std::uint64_t>(args.get_int("seed", 1, 0, 0x7fffffffffffffffl));
    const std::vector<Test> ts = tests(parse_widths(args.get("widths", "16,24")));

    std::vector<std::size_t> fam;
    const std::vector<Query> ex = extreme_queries(seed, n, &fam);
    const std::vector<Query> rq = random_queries(seed + 1, r);
    std::printf("%-8s %-20s %8s %8s %8s %8s\n", "queries", "test", "count", "real", "f.miss", "f.hit");
    for (const auto& [set, qs] : {std::pair{"extreme", &ex}, std::pair{"random", &rq}}) {
        if (qs->empty()) continue;
        std::vector<char> exact(qs->size());
        for (std::size_t i = 0; i < qs->size(); ++i) exact[i] = exact_hit((*qs)[i].ray, (*qs)[i].box);
        for (const Test& t : ts) {
            Tally all;
            std::vector<Tally> per(extreme_family_count());
            for (std::size_t i = 0; i < qs->size(); ++i) {
                const bool h = t.hit((*qs)[i]);
                all.add(exact[i], h);
                if (qs == &ex) per[fam[i]].add(exact[i], h);
            }
            print(set, t.name, all);
            if (args.has("families") && qs == &ex)
                for (std::size_t f = 0; f < per.size(); ++f)
                    if (per[f].false_misses || per[f].false_hits)
                        print("", std::string("  ") + extreme_family_name(f), per[f]);
        }
    }
    return 0;
}

}  // namespace pluecker::cli
