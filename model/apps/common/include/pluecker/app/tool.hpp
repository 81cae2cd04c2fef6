// SPDX-License-Identifier: MIT
// Shared by the benchmark programs (pluecker_bench, pluecker_tables,
// pluecker_peer): their options through the applications' option parser
// (args.hpp), per-thread CPU time, and main()'s mapping of errors to exit
// statuses.
#pragma once

#include "pluecker/app/args.hpp"

#include <cstdio>
#include <ctime>
#include <exception>
#include <set>
#include <string>
#include <vector>

namespace pluecker::app {

// argv[1, argc) with `options` (each takes a value) and the switch --help
// (or -h); any other argument is an InputError naming it.
inline Args tool_args(int argc, char** argv, const std::set<std::string>& options) {
    Args a(std::vector<std::string>(argv + 1, argv + argc), options, {"help"});
    for (const std::string& p : a.positional())
        if (p != "-h") throw InputError("unexpected argument '" + p + "'");
    return a;
}

// True when the tool was asked for its usage (--help or -h).
inline bool wants_help(const Args& a) { return a.has("help") || !a.positional().empty(); }

// CPU time of the calling thread: figures stay per-thread figures on a
// machine shared with other jobs.
inline double thread_seconds() {
    timespec ts{};
    clock_gettime(CLOCK_THREAD_CPUTIME_ID, &ts);
    return static_cast<double>(ts.tv_sec) + 1e-9 * static_cast<double>(ts.tv_nsec);
}

// Runs a tool's body: bad input (InputError) is exit status 2 with
// "<tool>: error: ...", anything else 1 with "<tool>: internal error: ...".
template <class Body>
int run_tool(const char* tool, Body&& body) {
    try {
        return body();
    } catch (const InputError& e) {
        std::fprintf(stderr, "%s: error: %s\n", tool, e.what());
        return 2;
    } catch (const std::exception& e) {
        std::fprintf(stderr, "%s: internal error: %s\n", tool, e.what());
        return 1;
    }
}

}  // namespace pluecker::app
