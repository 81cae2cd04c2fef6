// SPDX-License-Identifier: MIT
// The applications' one command-line parser (the `pluecker` subcommands,
// the benchmark programs, the Verilator harness): --name value options
// (or --name=value), --flag switches and positionals; every unknown or
// malformed flag is an InputError naming it.
#pragma once

#include "pluecker/geometry.hpp"

#include <map>
#include <set>
#include <string>
#include <vector>

namespace pluecker::app {

class Args {
public:
    // `options` take a value, `switches` do not.
    Args(const std::vector<std::string>& argv, const std::set<std::string>& options,
         const std::set<std::string>& switches);

    bool has(const std::string& name) const { return values_.count(name) > 0 || switches_.count(name) > 0; }
    // The value of an option (not a switch), else `fallback`.
    std::string get(const std::string& name, const std::string& fallback) const;
    // Integer option in [lo, hi]; InputError names the flag otherwise.
    long get_int(const std::string& name, long fallback, long lo, long hi) const;
    double get_double(const std::string& name, double fallback) const;
    // A comma-separated list; empty items are dropped, an empty list is an
    // InputError naming the flag. `fallback` when the option is absent.
    std::vector<std::string> get_list(const std::string& name, const std::vector<std::string>& fallback) const;
    const std::vector<std::string>& positional() const { return positional_; }

private:
    std::map<std::string, std::string> values_;  // options given, with their values
    std::set<std::string> switches_;             // switches given
    std::vector<std::string> positional_;
};

}  // namespace pluecker::app
