// SPDX-License-Identifier: MIT
#include "args.hpp"

#include <cerrno>
#include <cstdlib>

namespace pluecker::cli {

Args::Args(const std::vector<std::string>& argv, const std::set<std::string>& options,
           const std::set<std::string>& switches) {
    for (std::size_t i = 0; i < argv.size(); ++i) {
        const std::string& a = argv[i];
        if (a.rfind("--", 0) != 0 || a == "--") {
            positional_.push_back(a);
            continue;
        }
        std::string name = a.substr(2), value;
        const auto eq = name.find('=');
        const bool inline_value = eq != std::string::npos;
        if (inline_value) {
            value = name.substr(eq + 1);
            name = name.substr(0, eq);
        }
        if (switches.count(name)) {
            if (inline_value) throw InputError("option --" + name + " takes no value");
            values_[name] = "1";
        } else if (options.count(name)) {
            if (!inline_value) {
                if (i + 1 >= argv.size()) throw InputError("option --" + name + " needs a value");
                value = argv[++i];
            }
            values_[name] = value;
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

}  // namespace pluecker::cli
