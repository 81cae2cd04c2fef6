// SPDX-License-Identifier: MIT
// A small command-line parser for the `pluecker` subcommands: --name value
// options, --flag switches and positionals; every unknown or malformed flag
// is an InputError naming it.
#pragma once

#include "pluecker/geometry.hpp"

#include <map>
#include <set>
#include <string>
#include <vector>

namespace pluecker::cli {

class Args {
public:
    // `options` take a value, `switches` do not.
    Args(const std::vector<std::string>& argv, const std::set<std::string>& options,
         const std::set<std::string>& switches);

    bool has(const std::string& name) const { return values_.count(name) > 0; }
    std::string get(const std::string& name, const std::string& fallback) const;
    // Integer option in [lo, hi]; InputError names the flag otherwise.
    long get_int(const std::string& name, long fallback, long lo, long hi) const;
    double get_double(const std::string& name, double fallback) const;
    const std::vector<std::string>& positional() const { return positional_; }

private:
    std::map<std::string, std::string> values_;
    std::vector<std::string> positional_;
};

// Subcommands: each in its own file, each returns the exit status.
int cmd_query(const std::vector<std::string>& argv);
int cmd_render(const std::vector<std::string>& argv);
int cmd_trace(const std::vector<std::string>& argv);
int cmd_plan(const std::vector<std::string>& argv);
int cmd_study(const std::vector<std::string>& argv);
int cmd_contract(const std::vector<std::string>& argv);

}  // namespace pluecker::cli
