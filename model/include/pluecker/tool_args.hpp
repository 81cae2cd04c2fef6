// SPDX-License-Identifier: MIT
// Shared by the benchmark programs (pluecker_bench, pluecker_tables,
// pluecker_peer): option reading (`--name value` pairs, integers
// range-checked, errors as InputError naming the option), per-thread CPU
// time, and main()'s mapping of errors to exit statuses. The `pluecker` CLI
// has its own parser (model/cli/args.hpp) with subcommands and help texts.
#pragma once

#include <cstdio>
#include <cstdlib>
#include <ctime>
#include <exception>
#include <sstream>
#include <string>
#include <vector>

#include "pluecker/geometry.hpp"

namespace pluecker {

class ToolArgs {
public:
    ToolArgs(int argc, char** argv) : argc_(argc), argv_(argv) {}

    // Advances to the next option; false when all are read.
    bool next() {
        if (++i_ >= argc_) return false;
        name_ = argv_[i_];
        return true;
    }
    const std::string& name() const { return name_; }
    bool is(const char* option) const { return name_ == option; }

    std::string value() {
        if (i_ + 1 >= argc_) throw InputError("option " + name_ + " needs a value");
        return argv_[++i_];
    }

    long integer(long lo, long hi) {
        const std::string v = value();
        char* end = nullptr;
        const long n = std::strtol(v.c_str(), &end, 10);
        if (v.empty() || *end || n < lo || n > hi)
            throw InputError("option " + name_ + ": '" + v + "' is not an integer in " + std::to_string(lo) + ".." +
                             std::to_string(hi));
        return n;
    }

    // A comma-separated list; empty items are dropped, an empty list is an error.
    std::vector<std::string> list() {
        std::stringstream ss(value());
        std::vector<std::string> items;
        for (std::string item; std::getline(ss, item, ',');)
            if (!item.empty()) items.push_back(item);
        if (items.empty()) throw InputError("option " + name_ + ": empty list");
        return items;
    }

    [[noreturn]] void unknown() const { throw InputError("unknown option " + name_ + " (see --help)"); }

private:
    int argc_;
    char** argv_;
    int i_ = 0;
    std::string name_;
};

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

}  // namespace pluecker
