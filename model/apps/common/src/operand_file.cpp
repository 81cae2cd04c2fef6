// SPDX-License-Identifier: MIT
#include "pluecker/app/operand_file.hpp"

#include "pluecker/app/names.hpp"

#include <cerrno>
#include <cstring>
#include <fstream>
#include <ostream>
#include <sstream>

namespace pluecker::app {
namespace {

constexpr const char* kHeader = "operands";
constexpr int kFields = 17;
constexpr const char* kFieldNames[kFields] = {"cls", "ox", "oy", "oz", "dx",  "dy",  "dz",  "end_valid", "ex",
                                              "ey",  "ez", "lox", "loy", "loz", "hix", "hiy", "hiz"};

// The line without its comment, and whether anything is left.
std::string strip(const std::string& line) {
    const std::string s = line.substr(0, line.find('#'));
    return s.find_first_not_of(" \t\r") == std::string::npos ? std::string() : s;
}

std::ifstream open(const std::string& path) {
    std::ifstream in(path);
    if (!in) throw InputError(path + ": cannot open (" + std::strerror(errno) + ")");
    return in;
}

// "operands C D MODE" -> its format; InputError when malformed.
FixedFormat parse_header(const std::string& line, const std::string& where) {
    std::istringstream s(line);
    std::string word, mode, extra;
    FixedFormat f;
    if (!(s >> word) || word != kHeader || !(s >> f.coord_bits >> f.dir_bits >> mode) || (s >> extra))
        throw InputError(where + ": expected the header 'operands COORD_BITS DIR_BITS MODE'");
    try {
        f.validate();
        f.mode = parse_fixed_mode(mode);
    } catch (const InputError& e) {
        throw InputError(where + ": header: " + e.what());
    }
    return f;
}

// One integer field within [lo, hi].
std::int64_t field(std::istringstream& s, int k, std::int64_t lo, std::int64_t hi, const std::string& where) {
    std::string tok;
    if (!(s >> tok))
        throw InputError(where + ": expected " + std::to_string(kFields) + " integers, got " + std::to_string(k));
    std::size_t used = 0;
    long long v = 0;
    try {
        v = std::stoll(tok, &used, 10);
    } catch (const std::exception&) {
        used = 0;
    }
    if (used != tok.size())
        throw InputError(where + ": field " + std::to_string(k + 1) + " (" + kFieldNames[k] + "): '" + tok +
                         "' is not an integer");
    if (v < lo || v > hi)
        throw InputError(where + ": field " + std::to_string(k + 1) + " (" + kFieldNames[k] + "): " +
                         std::to_string(v) + " is outside its port range " + std::to_string(lo) + ".." +
                         std::to_string(hi));
    return v;
}

FixedQuery parse_operands(const std::string& line, const FixedFormat& f, const std::string& where) {
    std::istringstream s(line);
    const std::int64_t cmin = f.coord_min(), cmax = f.coord_max(), dmax = (std::int64_t{1} << f.dir_bits) - 1;
    int k = 0;
    FixedQuery q;
    q.ray.cls = static_cast<RayClass>(field(s, k++, 0, 7, where));
    for (auto& v : q.ray.org) v = field(s, k++, cmin, cmax, where);
    for (auto& v : q.ray.dir) v = field(s, k++, 0, dmax, where);
    q.ray.has_end = field(s, k++, 0, 1, where) != 0;
    for (auto& v : q.ray.end) v = field(s, k++, cmin, cmax, where);
    for (auto& v : q.box.lo) v = field(s, k++, cmin, cmax, where);
    for (auto& v : q.box.hi) v = field(s, k++, cmin, cmax, where);
    std::string extra;
    if (s >> extra) throw InputError(where + ": more than " + std::to_string(kFields) + " fields");
    return q;
}

std::string format_text(const FixedFormat& f) {
    return std::to_string(f.coord_bits) + " " + std::to_string(f.dir_bits) + " " + mode_name(f.mode);
}

}  // namespace

void write_operand_header(std::ostream& out, const FixedFormat& f) { out << kHeader << ' ' << format_text(f) << '\n'; }

void write_operands(std::ostream& out, const FixedQuery& q) {
    out << static_cast<int>(q.ray.cls);
    for (auto v : q.ray.org) out << ' ' << v;
    for (auto v : q.ray.dir) out << ' ' << v;
    out << ' ' << (q.ray.has_end ? 1 : 0);
    for (auto v : q.ray.end) out << ' ' << v;
    for (auto v : q.box.lo) out << ' ' << v;
    for (auto v : q.box.hi) out << ' ' << v;
    out << '\n';
}

bool is_operand_file(const std::string& path) {
    if (path == "-") return false;
    std::ifstream in(path);
    std::string line;
    while (in && std::getline(in, line)) {
        const std::string s = strip(line);
        if (s.empty()) continue;
        std::istringstream words(s);
        std::string first;
        words >> first;
        return first == kHeader;
    }
    return false;
}

std::vector<FixedQuery> read_operand_file(const std::string& path, const FixedFormat& f,
                                          std::vector<std::size_t>& lines) {
    std::ifstream in = open(path);
    std::vector<FixedQuery> out;
    lines.clear();
    bool header = false;
    std::string line;
    for (std::size_t n = 1; std::getline(in, line); ++n) {
        const std::string s = strip(line);
        if (s.empty()) continue;
        const std::string where = path + ":" + std::to_string(n);
        if (!header) {
            const FixedFormat h = parse_header(s, where);
            if (h.coord_bits != f.coord_bits || h.dir_bits != f.dir_bits || h.mode != f.mode)
                throw InputError(where + ": operands for " + format_text(h) + ", not " + format_text(f));
            header = true;
            continue;
        }
        out.push_back(parse_operands(s, f, where));
        lines.push_back(n);
    }
    if (in.bad()) throw InputError(path + ": read error");
    if (!header) throw InputError(path + ": no header 'operands COORD_BITS DIR_BITS MODE'");
    return out;
}

}  // namespace pluecker::app
