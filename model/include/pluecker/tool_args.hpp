// SPDX-License-Identifier: MIT
// Option reading for the benchmark programs (pluecker_bench, pluecker_tables,
// pluecker_peer): `--name value` pairs, integers range-checked, errors as
// InputError naming the option. The `pluecker` CLI has its own parser
// (model/cli/args.hpp) with subcommands and help texts.
#pragma once

#include <cstdlib>
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

}  // namespace pluecker
