// SPDX-License-Identifier: MIT
#include "pluecker/app/args.hpp"

#include <cerrno>
#include <cstdlib>
#include <sstream>

namespace pluecker::app {

Args::Args(const std::vector<std::string>& argv, const std::set<std::string>& options,
           const std::set<std::string>& switches) {
    for (std::size_t i = 0; i < argv.size(); ++i) {
        const std::string& a = argv[i];
        if (a.rfind("--", 0) != 0 || a == "--") {
            positional_.push_back(a);
            continue;
        }
        // "--name" or "--name=value": the name and, after '=', an inline value.
        const std::size_t eq = a.find('=', 2);
        const bool inline_value = eq != std::string::npos;
        const std::string name = a.substr(2, inline_value ? eq - 2 : std::string::npos);
        if (switches.count(name)) {
            if (inline_value) throw InputError("option --" + name + " takes no value");
            switches_.insert(name);
        } else if (options.count(name)) {
            if (inline_value) {
                values_[name] = a.substr(eq + 1);
            } else {
                if (i + 1 >= argv.size()) throw InputError("option --" + name + " needs a value");
                values_[name] = argv[++i];
            }
        } else {
            throw InputError("unknown option --" + name);
        }
    }
}

std::string Args::get(const std::string& name, const std::string& fallback) const {
    const auto it = values_.find(name);
    return it == values_.end() ? fallback : it->second;
}

long Args::get_int(const std::string& name, long fallback, long lo, long hi) const {
    if (!has(name)) return fallback;
    const std::string s = get(name, "");
    char* end = nullptr;
    errno = 0;
    const long v = std::strtol(s.c_str(), &end, 10);
    if (s.empty() || *end != '\0' || errno != 0)
        throw InputError("option --" + name + ": '" + s + "' is not an integer");
    if (v < lo || v > hi)
        throw InputError("option --" + name + ": " + s + " is outside " + std::to_string(lo) + ".." +
                         std::to_string(hi));
    return v;
}

double Args::get_double(const std::string& name, double fallback) const {
    if (!has(name)) return fallback;
    const std::string s = get(name, "");
    char* end = nullptr;
    const double v = std::strtod(s.c_str(), &end);
    if (s.empty() || *end != '\0' || v != v) throw InputError("option --" + name + ": '" + s + "' is not a number");
    return v;
}

std::vector<std::string> Args::get_list(const std::string& name, const std::vector<std::string>& fallback) const {
    if (!has(name)) return fallback;
    std::stringstream ss(get(name, ""));
    std::vector<std::string> items;
    for (std::string item; std::getline(ss, item, ',');)
        if (!item.empty()) items.push_back(item);
    if (items.empty()) throw InputError("option --" + name + ": empty list");
    return items;
}

}  // namespace pluecker::app
