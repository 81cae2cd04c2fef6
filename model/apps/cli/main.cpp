// SPDX-License-Identifier: MIT
// `pluecker`: the golden model's command line.
#include "commands.hpp"

#include "pluecker/mesh.hpp"

#include <cstdio>
#include <exception>
#include <string>
#include <vector>

namespace {

constexpr const char* kUsage =
    "usage: pluecker <command> [options]\n"
    "commands:\n"
    "  render   render a scene to PNG with statistics as JSON\n"
    "  query    answer ray/box queries from a file (1 = hit, 0 = miss)\n"
    "  trace    write the ray/box queries a traversal issues\n"
    "  plan     pick the smallest fixed-point widths a scene needs\n"
    "  study    extra traversal work and accuracy per fixed-point width\n"
    "  cascade  narrow ternary tests escalating their doubts to a wide one\n"
    "  contract the RTL's port contract; writes or checks its generated files\n"
    "  accuracy every box test (float, binary32 units, fixed point) against exact\n"
    "run 'pluecker <command> --help' for its options (render, trace, plan and\n"
    "study list the mesh file formats --scene reads)\n";

}  // namespace

int main(int argc, char** argv) {
    using namespace pluecker::cli;
    if (argc < 2 || std::string(argv[1]) == "--help" || std::string(argv[1]) == "-h") {
        std::fputs(kUsage, argc < 2 ? stderr : stdout);
        return argc < 2 ? 2 : 0;
    }
    const std::string cmd = argv[1];
    const std::vector<std::string> rest(argv + 2, argv + argc);
    pluecker::set_mesh_warning_handler(
        [cmd](const std::string& m) { std::fprintf(stderr, "pluecker %s: warning: %s\n", cmd.c_str(), m.c_str()); });
    try {
        if (cmd == "render") return cmd_render(rest);
        if (cmd == "query") return cmd_query(rest);
        if (cmd == "trace") return cmd_trace(rest);
        if (cmd == "plan") return cmd_plan(rest);
        if (cmd == "study") return cmd_study(rest);
        if (cmd == "cascade") return cmd_cascade(rest);
        if (cmd == "contract") return cmd_contract(rest);
        if (cmd == "accuracy") return cmd_accuracy(rest);
        std::fprintf(stderr, "pluecker: unknown command '%s'\n%s", cmd.c_str(), kUsage);
        return 2;
    } catch (const pluecker::InputError& e) {
        std::fprintf(stderr, "pluecker %s: error: %s\n", cmd.c_str(), e.what());
        return 2;
    } catch (const std::exception& e) {
        std::fprintf(stderr, "pluecker %s: internal error: %s\n", cmd.c_str(), e.what());
        return 1;
    }
}
