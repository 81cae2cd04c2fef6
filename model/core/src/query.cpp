// SPDX-License-Identifier: MIT
// The ray/box query text format (see query.hpp).
#include "pluecker/query.hpp"

#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <istream>
#include <ostream>

namespace pluecker {

namespace {

constexpr int kFields = 13;
constexpr const char* kFieldNames[kFields] = {"ox",   "oy",   "oz",   "dx",   "dy",   "dz",  "tmax",
                                              "minx", "miny", "minz", "maxx", "maxy", "maxz"};
constexpr const char* kAxisNames[3] = {"x", "y", "z"};

std::string num(float v) {
    char buf[48];
    std::snprintf(buf, sizeof buf, "%.9g", double(v));
    return buf;
}

// Round a double to float32 to nearest, ties to even; values beyond the
// float range (past the midpoint between FLT_MAX and 2^128) become +-inf.
// Written out because a C++ cast of an out-of-range double is undefined.
float to_float(double v) {
    constexpr double kOverflow = 0x1.ffffffp127;  // FLT_MAX + half an ulp: rounds to 2^128
    if (std::isfinite(v) && std::fabs(v) >= kOverflow) return std::signbit(v) ? -kInf : kInf;
    return static_cast<float>(v);
}

float field(const Query& q, int k) {
    if (k < 3) return q.ray.o[k];
    if (k < 6) return q.ray.d[k - 3];
    if (k == 6) return q.ray.tmax;
    if (k < 10) return q.box.lo[k - 7];
    return q.box.hi[k - 10];
}

void set_field(Query& q, int k, float v) {
    if (k < 3) q.ray.o[k] = v;
    else if (k < 6) q.ray.d[k - 3] = v;
    else if (k == 6) q.ray.tmax = v;
    else if (k < 10) q.box.lo[k - 7] = v;
    else q.box.hi[k - 10] = v;
}

bool is_coordinate(int k) { return k < 3 || k >= 7; }

// The "C" locale's white space (std::isspace is a slow library call).
bool is_space(char c) { return c == ' ' || c == '\t' || c == '\r' || c == '\n' || c == '\v' || c == '\f'; }

// A token for a message: a NUL byte is shown as \0, other control bytes as
// \xNN, so the message stays one readable line.
std::string printable(const char* tok, std::size_t n) {
    std::string out;
    for (std::size_t i = 0; i < n; ++i) {
        const auto c = static_cast<unsigned char>(tok[i]);
        if (c == 0) {
            out += "\\0";
        } else if (c < 0x20 || c == 0x7f) {
            char buf[8];
            std::snprintf(buf, sizeof buf, "\\x%02x", c);
            out += buf;
        } else {
            out.push_back(static_cast<char>(c));
        }
    }
    return out;
}

// Parses one line (comment already cut). Returns false for a blank line.
bool parse_line(std::string& line, const std::string& where, Query& q) {
    char* tokens[kFields + 1];
    std::size_t lengths[kFields + 1];
    int count = 0;
    char* s = line.data();
    char* const end = s + line.size();
    while (s < end) {
        while (s < end && is_space(*s)) ++s;
        if (s == end) break;
        char* tok = s;
        while (s < end && !is_space(*s)) ++s;
        *s = '\0';  // s < end here, or s == end points at the string's own terminator
        if (count <= kFields) {
            tokens[count] = tok;
            lengths[count] = std::size_t(s - tok);
        }
        ++count;
        ++s;
    }
    if (count == 0) return false;
    if (count != kFields)
        throw InputError(where + ": expected 13 numbers (ox oy oz dx dy dz tmax minx miny minz maxx maxy maxz), found " +
                         std::to_string(count));
    for (int k = 0; k < kFields; ++k) {
        char* stop = nullptr;
        const double v = std::strtod(tokens[k], &stop);
        // The token ends at tokens[k] + lengths[k]: a NUL byte inside it
        // stops strtod early and must not pass for the token's end.
        if (stop == tokens[k] || stop != tokens[k] + lengths[k])
            throw InputError(where + ": field " + std::to_string(k + 1) + " (" + kFieldNames[k] + "): cannot parse '" +
                             printable(tokens[k], lengths[k]) + "' as a number");
        set_field(q, k, to_float(v));
    }
    validate_query(q, where);
    return true;
}

}  // namespace

void validate_query(const Query& q, const std::string& where) {
    for (int k = 0; k < kFields; ++k)
        if (std::isnan(field(q, k))) throw InputError(where + ": " + kFieldNames[k] + " is NaN");
    for (int k = 0; k < kFields; ++k)
        if (is_coordinate(k) && std::isinf(field(q, k)))
            throw InputError(where + ": " + kFieldNames[k] + " is not a finite coordinate (" + num(field(q, k)) + ")");
    for (int k = 3; k < 6; ++k)
        if (std::isinf(field(q, k)))
            throw InputError(where + ": " + kFieldNames[k] + " is not a finite direction component (" +
                             num(field(q, k)) + ")");
    if (q.ray.d.x == 0.0f && q.ray.d.y == 0.0f && q.ray.d.z == 0.0f)
        throw InputError(where + ": direction is zero (dx = dy = dz = 0)");
    if (q.ray.tmax < 0.0f) throw InputError(where + ": tmax is negative (" + num(q.ray.tmax) + ")");
    for (int a = 0; a < 3; ++a)
        if (q.box.lo[a] > q.box.hi[a])
            throw InputError(where + ": box min > max on axis " + kAxisNames[a] + " (min" + kAxisNames[a] + " = " +
                             num(q.box.lo[a]) + " > max" + kAxisNames[a] + " = " + num(q.box.hi[a]) + ")");
}

std::vector<Query> read_queries(std::istream& in, const std::string& source, std::vector<std::size_t>* lines) {
    std::vector<Query> out;
    if (lines) lines->clear();
    std::string line;
    std::size_t number = 0;
    while (std::getline(in, line)) {
        ++number;
        const auto hash = line.find('#');
        if (hash != std::string::npos) line.resize(hash);
        Query q;
        if (!parse_line(line, source + ":" + std::to_string(number), q)) continue;
        out.push_back(q);
        if (lines) lines->push_back(number);
    }
    if (in.bad()) throw InputError(source + ": read error");
    return out;
}

std::vector<Query> read_queries(std::istream& in, const std::string& source) {
    return read_queries(in, source, nullptr);
}

std::vector<Query> read_queries_file(const std::string& path) {
    std::ifstream in(path);
    if (!in) throw InputError(path + ": cannot open (" + std::strerror(errno) + ")");
    return read_queries(in, path);
}

void write_query(std::ostream& out, const Query& q) {
    char buf[kFields * 24 + 2];
    int n = 0;
    for (int k = 0; k < kFields; ++k)
        n += std::snprintf(buf + n, sizeof buf - n, k ? " %a" : "%a", double(field(q, k)));
    buf[n++] = '\n';
    out.write(buf, n);
}

}  // namespace pluecker
