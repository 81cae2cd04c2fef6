// SPDX-License-Identifier: MIT
// The entry point the harnesses share (pluecker_sim of the global and the
// binary32 units, pluecker_sim_local):
// usage and --help, the subcommand dispatch and the exit statuses (0 ok,
// 1 mismatch or RTL protocol error, 2 bad input or options).
#pragma once

#include "rtl_stream.hpp"

#include "pluecker/geometry.hpp"  // InputError

#include <cstdio>
#include <exception>
#include <initializer_list>
#include <string>
#include <vector>

namespace pluecker::sim {

struct HarnessCommand {
    const char* name;
    int (*run)(const std::vector<std::string>& argv);
};

inline int harness_main(int argc, char** argv, const char* prog, const char* usage, const std::string& built_for,
                        std::initializer_list<HarnessCommand> commands) {
    Verilated::commandArgs(1, argv);  // no plusargs reach the model
    if (argc < 2 || std::string(argv[1]) == "--help" || std::string(argv[1]) == "-h") {
        std::fputs(usage, argc < 2 ? stderr : stdout);
        if (argc >= 2) std::printf("built for: %s\n", built_for.c_str());
        return argc < 2 ? 2 : 0;
    }
    const std::string cmd = argv[1];
    const std::vector<std::string> rest(argv + 2, argv + argc);
    try {
        for (const HarnessCommand& c : commands)
            if (cmd == c.name) return c.run(rest);
        std::fprintf(stderr, "%s: unknown command '%s'\n%s", prog, cmd.c_str(), usage);
        return 2;
    } catch (const InputError& e) {
        std::fprintf(stderr, "%s %s: error: %s\n", prog, cmd.c_str(), e.what());
        return 2;
    } catch (const ProtocolError& e) {
        std::fprintf(stderr, "%s %s: RTL protocol error: %s\n", prog, cmd.c_str(), e.what());
        return 1;
    } catch (const std::exception& e) {
        std::fprintf(stderr, "%s %s: internal error: %s\n", prog, cmd.c_str(), e.what());
        return 1;
    }
}

}  // namespace pluecker::sim
