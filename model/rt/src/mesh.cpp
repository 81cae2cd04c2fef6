// SPDX-License-Identifier: MIT
// Mesh bounds, normalisation into the scene cube, and mesh file loading
// (every format Assimp reads; OBJ and PLY get extra checks).
#include "pluecker/mesh.hpp"

#include <assimp/DefaultLogger.hpp>
#include <assimp/Importer.hpp>
#include <assimp/LogStream.hpp>
#include <assimp/importerdesc.h>
#include <assimp/material.h>
#include <assimp/postprocess.h>
#include <assimp/scene.h>

#include <glm/common.hpp>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <cctype>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <functional>
#include <iterator>
#include <limits>
#include <mutex>
#include <optional>
#include <sstream>
#include <string_view>

namespace pluecker {

namespace {

void default_warning(const std::string& message) { std::fprintf(stderr, "warning: %s\n", message.c_str()); }

std::function<void(const std::string&)>& warning_sink() {
    static std::function<void(const std::string&)> sink = default_warning;
    return sink;
}

void warn(const std::string& message) { warning_sink()(message); }

}  // namespace

void set_mesh_warning_handler(std::function<void(const std::string&)> handler) {
    warning_sink() = handler ? std::move(handler) : default_warning;
}

std::vector<MeshFormat> mesh_formats() {
    Assimp::Importer imp;
    std::vector<MeshFormat> out;
    for (std::size_t i = 0; i < imp.GetImporterCount(); ++i) {
        const aiImporterDesc* d = imp.GetImporterInfo(i);
        if (!d) continue;
        MeshFormat f;
        f.name = d->mName;
        std::istringstream exts(d->mFileExtensions ? d->mFileExtensions : "");
        for (std::string e; exts >> e;) f.extensions.push_back("." + e);
        if (!f.extensions.empty()) out.push_back(std::move(f));
    }
    return out;
}

std::string mesh_extensions() {
    std::vector<std::string> all;
    for (const MeshFormat& f : mesh_formats()) all.insert(all.end(), f.extensions.begin(), f.extensions.end());
    std::sort(all.begin(), all.end());
    all.erase(std::unique(all.begin(), all.end()), all.end());
    std::string out;
    for (const std::string& e : all) out += (out.empty() ? "" : " ") + e;
    return out;
}

Box Mesh::bounds() const {
    Box b;
    for (const Vec3& v : vertices) b.grow(v);
    return b;
}

void normalize_to_cube(Mesh& m) {
    if (m.vertices.empty()) throw InputError(m.name + ": empty mesh, cannot normalise");
    const Box b = m.bounds();
    double ext = 0.0;  // in double: hi - lo of two floats is exact
    for (int a = 0; a < 3; ++a) ext = std::max(ext, double(b.hi[a]) - double(b.lo[a]));
    if (!(ext > 0.0) || !std::isfinite(ext))
        throw InputError(m.name + ": mesh has zero or non-finite extent, cannot normalise");
    // In double the extent, the centre c and lo - c are exact, so the largest
    // axis maps to -1 and +1 within an ulp of double and rounds to exactly
    // -1.0f and 1.0f; the clamp only guards against a last-ulp overshoot.
    const double s = 2.0 / ext;
    double c[3];
    for (int a = 0; a < 3; ++a) c[a] = 0.5 * (double(b.lo[a]) + double(b.hi[a]));
    for (Vec3& v : m.vertices)
        for (int a = 0; a < 3; ++a) {
            const float x = static_cast<float>((double(v[a]) - c[a]) * s);
            v[a] = std::clamp(x, -1.0f, 1.0f);
        }
}

namespace {

std::string lower_extension(const std::string& path) {
    std::string ext = std::filesystem::path(path).extension().string();
    for (char& ch : ext) ch = static_cast<char>(std::tolower(static_cast<unsigned char>(ch)));
    return ext;
}

void check_readable(const std::string& path) {
    std::error_code ec;
    const auto st = std::filesystem::status(path, ec);
    if (!std::filesystem::exists(st)) throw InputError(path + ": no such file");
    if (!std::filesystem::is_regular_file(st)) throw InputError(path + ": not a regular file");
    const std::string ext = lower_extension(path);
    if (ext.size() < 2 || !Assimp::Importer().IsExtensionSupported(ext))
        throw InputError(path + ": unknown mesh extension '" + ext + "' (supported: " + mesh_extensions() + ")");
    if (std::filesystem::file_size(path, ec) == 0) throw InputError(path + ": empty mesh (empty file)");
}

// A word of the input for a message: control and non-ASCII bytes as \xNN,
// cut after 40 characters.
std::string printable(std::string_view word) {
    std::string out;
    for (char ch : word.substr(0, 40)) {
        const auto c = static_cast<unsigned char>(ch);
        if (c >= 0x20 && c < 0x7f) {
            out.push_back(ch);
        } else {
            char buf[8];
            std::snprintf(buf, sizeof buf, "\\x%02x", c);
            out += buf;
        }
    }
    if (word.size() > 40) out += "...";
    return out;
}

// ---------------------------------------------------------------------------
// PLY structure check. Assimp 5.2's PLY reader loops forever on a header
// without end_header, silently reads past the end of a truncated body
// (zeros or garbage become vertices and faces), and walks every item of a
// vertex or face element even when the element has no properties (about
// 4e9 empty iterations for 'element face 4294967295'; a bad_alloc for an
// 'edge' or 'material' element). So the header is parsed strictly here
// (element and property lines exactly as the PLY format has them, nothing
// after the count or the name, counts below 2^32 as Assimp stores them, no
// element with items but no properties) and the body layout is walked; the
// values themselves are left to Assimp.

struct PlyProperty {
    int size = 0;        // bytes of a scalar, or of a list's items
    int count_size = 0;  // bytes of a list's count; 0 for a scalar
};
struct PlyElement {
    std::string name;
    std::uint64_t count = 0;
    int line = 0;  // of the header, for messages
    std::vector<PlyProperty> props;
};
struct PlyHeader {
    std::string format;
    std::vector<PlyElement> elements;
    std::size_t body = 0;  // offset of the first body byte
};

int ply_type_size(const std::string& t) {
    if (t == "char" || t == "uchar" || t == "int8" || t == "uint8") return 1;
    if (t == "short" || t == "ushort" || t == "int16" || t == "uint16") return 2;
    if (t == "int" || t == "uint" || t == "float" || t == "int32" || t == "uint32" || t == "float32") return 4;
    if (t == "double" || t == "float64") return 8;
    return 0;
}

// Edit distance of two short words (insertions, deletions, substitutions).
std::size_t edit_distance(std::string_view a, std::string_view b) {
    std::vector<std::size_t> row(b.size() + 1);
    for (std::size_t j = 0; j <= b.size(); ++j) row[j] = j;
    for (std::size_t i = 1; i <= a.size(); ++i) {
        std::size_t diag = row[0];
        row[0] = i;
        for (std::size_t j = 1; j <= b.size(); ++j) {
            const std::size_t up = row[j];
            row[j] = std::min({row[j] + 1, row[j - 1] + 1, diag + (a[i - 1] != b[j - 1] ? 1 : 0)});
            diag = up;
        }
    }
    return row[b.size()];
}

// The structural header keyword a word is a misspelling of (at most two
// edits, case ignored), or null.
const char* near_ply_keyword(const std::string& word) {
    if (word.size() > 16) return nullptr;
    std::string w = word;
    for (char& ch : w) ch = static_cast<char>(std::tolower(static_cast<unsigned char>(ch)));
    for (const char* k : {"format", "element", "property", "end_header"})
        if (edit_distance(w, k) <= 2) return k;
    return nullptr;
}

PlyHeader parse_ply_header(const std::string& data, const std::string& path) {
    PlyHeader h;
    std::size_t pos = 0;
    int line_no = 0;
    auto fail = [&](const std::string& what) {
        throw InputError(path + ":" + std::to_string(line_no) + ": PLY header: " + what);
    };
    for (;;) {
        const std::size_t nl = data.find('\n', pos);
        ++line_no;
        if (nl == std::string::npos) fail("no end_header line (truncated file?)");
        std::string line = data.substr(pos, nl - pos);
        pos = nl + 1;
        if (!line.empty() && line.back() == '\r') line.pop_back();
        std::istringstream ls(line);
        std::string kw;
        ls >> kw;
        auto no_more_words = [&](const std::string& after) {
            std::string extra;
            if (ls >> extra) fail("unexpected '" + printable(extra) + "' after " + after);
        };
        if (line_no == 1) {
            if (kw != "ply") fail("first line is not 'ply'");
        } else if (kw == "format") {
            ls >> h.format;
            if (h.format != "ascii" && h.format != "binary_little_endian" && h.format != "binary_big_endian")
                fail("unknown format '" + h.format + "'");
        } else if (kw == "element") {
            PlyElement e;
            e.line = line_no;
            std::string count;
            if (!(ls >> e.name >> count)) fail("malformed element line (expected 'element NAME COUNT')");
            const auto [ptr, ec] = std::from_chars(count.data(), count.data() + count.size(), e.count);
            if (ec == std::errc::result_out_of_range || (ec == std::errc{} && e.count > 0xffffffffu))
                fail("element '" + printable(e.name) + "': count " + printable(count) + " exceeds 4294967295");
            if (ec != std::errc{} || ptr != count.data() + count.size())
                fail("element '" + printable(e.name) + "': count '" + printable(count) + "' is not a whole number");
            no_more_words("the count of element '" + printable(e.name) + "'");
            h.elements.push_back(e);
        } else if (kw == "property") {
            if (h.elements.empty()) fail("property before any element");
            std::string type, name;
            PlyProperty p;
            ls >> type;
            if (type == "list") {
                std::string ct, it;
                ls >> ct >> it;
                p.count_size = ply_type_size(ct);
                p.size = ply_type_size(it);
                if (p.count_size == 0 || p.size == 0)
                    fail("unknown list type '" + printable(ct) + " " + printable(it) + "'");
            } else {
                p.size = ply_type_size(type);
                if (p.size == 0) fail("unknown property type '" + printable(type) + "'");
            }
            if (!(ls >> name)) fail("property without a name");
            no_more_words("property '" + printable(name) + "'");
            h.elements.back().props.push_back(p);
        } else if (kw == "end_header") {
            break;
        } else if (kw != "comment" && kw != "obj_info" && !kw.empty()) {
            // Some writers put a bare line in the header (Blender 2.47:
            // 'Created by Blender3D 247 - www.blender3d.com - file: ...');
            // Assimp skips it, so it is read as a comment. A misspelt
            // structural keyword is still an error: skipping it would
            // change the body's layout.
            if (const char* near = near_ply_keyword(kw))
                fail("unknown keyword '" + printable(kw) + "' (did you mean '" + near + "'?)");
            if (!std::isalpha(static_cast<unsigned char>(kw[0])))  // data: the header ended unmarked
                fail("unknown keyword '" + printable(kw) + "' (a data line before end_header?)");
            warn(path + ":" + std::to_string(line_no) + ": PLY header: line without a keyword taken as a comment: '" +
                 printable(line) + "'");
        }
    }
    if (h.format.empty()) throw InputError(path + ": PLY header has no format line");
    for (const PlyElement& e : h.elements)
        if (e.count > 0 && e.props.empty())
            throw InputError(path + ":" + std::to_string(e.line) + ": PLY header: element '" + printable(e.name) +
                             "' has " + std::to_string(e.count) + " items but no properties");
    h.body = pos;
    return h;
}

std::uint64_t read_uint(const char* p, int size, bool big_endian) {
    std::uint64_t v = 0;
    for (int i = 0; i < size; ++i) {
        const auto byte = static_cast<unsigned char>(p[big_endian ? i : size - 1 - i]);
        v = (v << 8) | byte;
    }
    return v;
}

[[noreturn]] void ply_truncated(const std::string& path, const PlyElement& e, std::uint64_t item) {
    throw InputError(path + ": truncated PLY: element '" + e.name + "' item " + std::to_string(item) + " of " +
                     std::to_string(e.count) + " runs past the end of the file");
}

void walk_ply_binary(const std::string& data, const PlyHeader& h, const std::string& path) {
    const bool big = h.format == "binary_big_endian";
    std::uint64_t pos = h.body;
    const std::uint64_t end = data.size();
    for (const PlyElement& e : h.elements) {
        const bool fixed = std::all_of(e.props.begin(), e.props.end(), [](auto& p) { return p.count_size == 0; });
        if (fixed) {  // one multiplication instead of a walk
            std::uint64_t stride = 0;
            for (const PlyProperty& p : e.props) stride += std::uint64_t(p.size);
            if (stride != 0 && e.count > (end - pos) / stride) ply_truncated(path, e, (end - pos) / stride);
            pos += stride * e.count;
            continue;
        }
        for (std::uint64_t item = 0; item < e.count; ++item)
            for (const PlyProperty& p : e.props) {
                std::uint64_t n = 1;
                if (p.count_size != 0) {
                    if (end - pos < std::uint64_t(p.count_size)) ply_truncated(path, e, item);
                    n = read_uint(data.data() + pos, p.count_size, big);
                    pos += std::uint64_t(p.count_size);
                }
                if (n > (end - pos) / std::uint64_t(p.size)) ply_truncated(path, e, item);
                pos += n * std::uint64_t(p.size);
            }
    }
}

void walk_ply_ascii(const std::string& data, const PlyHeader& h, const std::string& path) {
    std::size_t pos = h.body;
    auto next_token = [&](std::string_view& tok) {
        while (pos < data.size() && std::isspace(static_cast<unsigned char>(data[pos]))) ++pos;
        if (pos == data.size()) return false;
        const std::size_t start = pos;
        while (pos < data.size() && !std::isspace(static_cast<unsigned char>(data[pos]))) ++pos;
        tok = std::string_view(data).substr(start, pos - start);
        return true;
    };
    std::string_view tok;
    for (const PlyElement& e : h.elements) {
        if (e.props.empty()) continue;  // items without properties take no tokens
        for (std::uint64_t item = 0; item < e.count; ++item)
            for (const PlyProperty& p : e.props) {
                if (!next_token(tok)) ply_truncated(path, e, item);
                if (p.count_size == 0) continue;
                std::uint64_t n = 0;
                const auto [ptr, ec] = std::from_chars(tok.data(), tok.data() + tok.size(), n);
                if (ec != std::errc{} || ptr != tok.data() + tok.size())
                    throw InputError(path + ": PLY element '" + e.name + "' item " + std::to_string(item) +
                                     ": bad list length '" + std::string(tok) + "'");
                for (std::uint64_t k = 0; k < n; ++k)
                    if (!next_token(tok)) ply_truncated(path, e, item);
            }
    }
}

void check_ply_structure(const std::string& path) {
    std::ifstream in(path, std::ios::binary);
    if (!in) throw InputError(path + ": cannot open");
    const std::string data((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    const PlyHeader h = parse_ply_header(data, path);
    if (h.format == "ascii")
        walk_ply_ascii(data, h, path);
    else
        walk_ply_binary(data, h, path);
}

// glTF 1.0, which Assimp 5.2 reads wrongly: its binary files load with the
// meshes misplaced (a round trip through Assimp's own glTF 1.0 writer moves
// them), and its reader can stop the process on an internal assertion.
// glTF 2.0 (what Blender and current tools write) is read. The version is
// asset.version in a .gltf file, the header's in a .glb file.
void refuse_gltf1(const std::string& path) {
    const std::string ext = lower_extension(path);
    if (ext != ".gltf" && ext != ".glb") return;
    std::ifstream in(path, std::ios::binary);
    std::string version;
    if (ext == ".glb") {
        unsigned char head[8] = {};
        in.read(reinterpret_cast<char*>(head), 8);
        if (in.gcount() == 8 && std::string(reinterpret_cast<char*>(head), 4) == "glTF")
            version = std::to_string(head[4] | head[5] << 8 | head[6] << 16 | unsigned(head[7]) << 24);
    } else {
        const nlohmann::json j = nlohmann::json::parse(in, nullptr, /*allow_exceptions=*/false);
        if (j.is_object() && j.contains("asset") && j["asset"].is_object() && j["asset"].contains("version") &&
            j["asset"]["version"].is_string())
            version = j["asset"]["version"].get<std::string>();
    }
    if (version == "1" || version.rfind("1.", 0) == 0)
        throw InputError(path + ": glTF " + (version == "1" ? "1.0" : version) +
                         " is not supported (Assimp 5.2 misplaces its meshes); export it as glTF 2.0");
}

// ---------------------------------------------------------------------------
// OBJ face index errors. Assimp reports a bad index of an 'f', 'l' or 'p'
// line ("OBJ: vertex index out of range", "OBJ: Invalid face index.")
// without its line, so after such a failure the file is scanned with
// Assimp's rules to find it: a component that reads as 0 (or not as a
// number) is invalid; a vertex index i > 0 must be at most the file's
// vertex count, i < 0 counts back from the vertices read so far. Like
// Assimp, only a 'v' line of 3, 4 (homogeneous) or 6 (with colour) numbers
// counts as a vertex.

struct ObjIndexProblem {
    std::size_t line = 0;
    std::string what;
};

std::optional<ObjIndexProblem> find_obj_index_problem(const std::string& path) {
    std::ifstream in(path, std::ios::binary);
    std::vector<std::string> lines;
    for (std::string l; std::getline(in, l);) lines.push_back(std::move(l));
    auto is_blank = [](char c) { return c == ' ' || c == '\t' || c == '\r'; };
    auto starts = [&](const std::string& l, char kw) {
        std::size_t i = 0;
        while (i < l.size() && is_blank(l[i])) ++i;
        return i + 1 < l.size() && l[i] == kw && is_blank(l[i + 1]) ? i + 2 : std::string::npos;
    };
    auto is_vertex = [&](const std::string& l) {
        const std::size_t pos = starts(l, 'v');
        if (pos == std::string::npos) return false;
        std::istringstream ws(l.substr(pos));
        int words = 0;
        for (std::string w; ws >> w;) ++words;
        return words == 3 || words == 4 || words == 6;
    };
    long long total = 0;
    for (const std::string& l : lines)
        if (is_vertex(l)) ++total;
    long long so_far = 0;
    for (std::size_t n = 0; n < lines.size(); ++n) {
        const std::string& l = lines[n];
        if (starts(l, 'v') != std::string::npos) {
            if (is_vertex(l)) ++so_far;
            continue;
        }
        std::size_t pos = std::string::npos;
        for (char kw : {'f', 'l', 'p'})
            if (pos == std::string::npos) pos = starts(l, kw);
        if (pos == std::string::npos) continue;
        std::istringstream ws(l.substr(pos));
        for (std::string word; ws >> word;) {
            std::size_t start = 0;
            for (int component = 0; start <= word.size(); ++component) {
                const std::size_t slash = std::min(word.find('/', start), word.size());
                const std::string part = word.substr(start, slash - start);
                start = slash + 1;
                if (part.empty()) continue;
                const long long i = std::strtoll(part.c_str(), nullptr, 10);
                if (i == 0) return ObjIndexProblem{n + 1, "index '" + printable(part) + "' is not a number or 0"};
                if (component != 0) continue;
                if (i > total)
                    return ObjIndexProblem{n + 1, "vertex index " + std::to_string(i) + ", the file has " +
                                                      std::to_string(total) + " vertices"};
                if (i < 0 && so_far + i < 0)
                    return ObjIndexProblem{n + 1, "vertex index " + std::to_string(i) + " with " +
                                                      std::to_string(so_far) + " vertices before this line"};
            }
        }
    }
    return std::nullopt;
}

// Assimp's failure message, with the file's line when it is an OBJ face
// index error that the scan above can place.
std::string load_failure(const std::string& path, std::string reason) {
    if (lower_extension(path) == ".obj" &&
        (reason.find("index out of range") != std::string::npos || reason.find("Invalid face index") != std::string::npos))
        if (const auto p = find_obj_index_problem(path)) {
            if (!reason.empty() && reason.back() == '.') reason.pop_back();
            return path + ":" + std::to_string(p->line) + ": cannot load mesh: " + reason + " (" + p->what + ")";
        }
    return path + ": cannot load mesh: " + reason;
}

std::string mesh_label(const aiScene& sc, unsigned mi) {
    return sc.mNumMeshes > 1 ? " of mesh " + std::to_string(mi) : std::string();
}

// Checked on Assimp's raw import, before any post-processing step runs:
// Assimp's PLY reader passes out-of-range indices (and garbage from a
// truncated binary file) and empty faces (truncated ASCII file) straight
// through, and its Triangulate and JoinIdenticalVertices steps would read
// out of bounds or abort on them. Vertex indices here are those of the raw
// import: for a PLY file, the file's vertex index; for OBJ, one vertex per
// face corner.
void check_raw(const aiScene& sc, const std::string& path) {
    for (unsigned mi = 0; mi < sc.mNumMeshes; ++mi) {
        const aiMesh& am = *sc.mMeshes[mi];
        for (unsigned vi = 0; vi < am.mNumVertices; ++vi) {
            const aiVector3D& p = am.mVertices[vi];
            if (std::isfinite(p.x) && std::isfinite(p.y) && std::isfinite(p.z)) continue;
            std::ostringstream os;
            os << path << ": non-finite coordinate at vertex " << vi << mesh_label(sc, mi) << " (" << p.x << ' '
               << p.y << ' ' << p.z << ')';
            throw InputError(os.str());
        }
        for (unsigned fi = 0; fi < am.mNumFaces; ++fi) {
            const aiFace& f = am.mFaces[fi];
            if (f.mNumIndices == 0)
                throw InputError(path + ": face " + std::to_string(fi) + mesh_label(sc, mi) +
                                 " has no vertex indices (truncated or malformed file)");
            for (unsigned k = 0; k < f.mNumIndices; ++k) {
                if (f.mIndices[k] < am.mNumVertices) continue;
                std::ostringstream os;
                os << path << ": vertex index " << f.mIndices[k] << " out of range (" << am.mNumVertices
                   << " vertices) in face " << fi << mesh_label(sc, mi) << " (truncated or malformed file?)";
                throw InputError(os.str());
            }
        }
    }
}

Material to_material(const aiMaterial& am) {
    Material m;
    aiString name;
    if (am.Get(AI_MATKEY_NAME, name) == AI_SUCCESS && std::string(name.C_Str()) == AI_DEFAULT_MATERIAL_NAME)
        return m;
    aiColor3D c;
    if (am.Get(AI_MATKEY_COLOR_DIFFUSE, c) == AI_SUCCESS) m.color = Vec3(c.r, c.g, c.b);
    float opacity = 1.0f;
    if (am.Get(AI_MATKEY_OPACITY, opacity) == AI_SUCCESS && opacity < 1.0f) {
        m.kind = MaterialKind::Glass;
        float ior = 0.0f;
        if (am.Get(AI_MATKEY_REFRACTI, ior) == AI_SUCCESS && ior >= 1.0f) m.ior = ior;
    }
    return m;
}

// A node's transformation in double (Assimp's IsIdentity() has a tolerance;
// identity here is exact).
using Affine = std::array<double, 12>;  // row-major 3x4
constexpr Affine kIdentity{1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0};

Affine compose(const Affine& a, const aiMatrix4x4& m) {
    const double b[12] = {m.a1, m.a2, m.a3, m.a4, m.b1, m.b2, m.b3, m.b4, m.c1, m.c2, m.c3, m.c4};
    Affine r{};
    for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 4; ++j)
            r[4 * i + j] = a[4 * i] * b[j] + a[4 * i + 1] * b[4 + j] + a[4 * i + 2] * b[8 + j] + (j == 3 ? a[4 * i + 3] : 0.0);
    return r;
}

// Every placement of every mesh in the node hierarchy (formats such as
// glTF, FBX, Collada and 3DS place meshes with node transformations; OBJ,
// PLY, STL and OFF put them all at the root with the identity), in a
// depth-first walk from the root.
void collect_placements(const aiNode& node, const Affine& parent, std::vector<std::vector<Affine>>& out, int depth,
                        const std::string& path) {
    if (depth > 1000) throw InputError(path + ": node hierarchy deeper than 1000 (cyclic?)");
    const Affine world = compose(parent, node.mTransformation);
    for (unsigned k = 0; k < node.mNumMeshes; ++k)
        if (node.mMeshes[k] < out.size()) out[node.mMeshes[k]].push_back(world);
    for (unsigned c = 0; c < node.mNumChildren; ++c)
        if (node.mChildren[c]) collect_placements(*node.mChildren[c], world, out, depth + 1, path);
}

void append_mesh(Mesh& out, const aiMesh& am, const Affine& xf, const std::string& path) {
    const std::size_t base = out.vertices.size();
    if (base + am.mNumVertices > std::numeric_limits<std::uint32_t>::max())
        throw InputError(path + ": more than 2^32-1 vertices");
    const bool identity = xf == kIdentity;
    for (unsigned vi = 0; vi < am.mNumVertices; ++vi) {
        const aiVector3D& p = am.mVertices[vi];
        if (identity) {
            out.vertices.emplace_back(p.x, p.y, p.z);
            continue;
        }
        float q[3];
        for (int i = 0; i < 3; ++i)
            q[i] = static_cast<float>(xf[4 * i] * p.x + xf[4 * i + 1] * p.y + xf[4 * i + 2] * p.z + xf[4 * i + 3]);
        if (!(std::isfinite(q[0]) && std::isfinite(q[1]) && std::isfinite(q[2]))) {
            std::ostringstream os;
            os << path << ": non-finite coordinate at vertex " << vi << " after the node transformation ("
               << q[0] << ' ' << q[1] << ' ' << q[2] << ')';
            throw InputError(os.str());
        }
        out.vertices.emplace_back(q[0], q[1], q[2]);
    }
    const auto mat = static_cast<std::uint16_t>(am.mMaterialIndex);
    for (unsigned fi = 0; fi < am.mNumFaces; ++fi) {
        const aiFace& f = am.mFaces[fi];
        if (f.mNumIndices != 3) continue;  // points and lines (triangulation leaves no polygons)
        std::array<std::uint32_t, 3> t{};
        for (int k = 0; k < 3; ++k) {
            if (f.mIndices[k] >= am.mNumVertices) {
                std::ostringstream os;
                os << path << ": vertex index " << f.mIndices[k] << " out of range (" << am.mNumVertices
                   << " vertices) in face " << fi;
                throw InputError(os.str());
            }
            t[k] = static_cast<std::uint32_t>(base + f.mIndices[k]);
        }
        out.triangles.push_back(t);
        out.tri_material.push_back(mat);
    }
}

// Assimp's error-level log messages during one import. Most are about what
// a renderer of the mesh can do without (a missing .mtl file, a vertex
// colour layer, a default material) and become warnings; but some
// importers log an out-of-range index and go on with made-up data (the OFF
// reader replaces the index and keeps the face), so a message about
// something out of range refuses the file. Assimp's logger is
// process-wide: loads are serialised.
class ImportErrors : public Assimp::LogStream {
public:
    ImportErrors() {
        Assimp::DefaultLogger::create(nullptr, Assimp::Logger::NORMAL, 0);
        Assimp::DefaultLogger::get()->attachStream(this, Assimp::Logger::Err);
    }
    ~ImportErrors() override {
        Assimp::DefaultLogger::get()->detachStream(this, Assimp::Logger::Err);
        Assimp::DefaultLogger::kill();
    }
    ImportErrors(const ImportErrors&) = delete;
    ImportErrors& operator=(const ImportErrors&) = delete;
    void write(const char* message) override {
        std::string m = message;
        while (!m.empty() && (m.back() == '\n' || m.back() == '\r')) m.pop_back();
        if (const auto colon = m.find(": "); m.rfind("Error, ", 0) == 0 && colon != std::string::npos)
            m.erase(0, colon + 2);  // "Error, T0: " prefix
        all.push_back(m);
    }
    std::vector<std::string> all;
};

std::mutex& import_mutex() {
    static std::mutex m;
    return m;
}

}  // namespace

Mesh load_mesh_file(const std::string& path) {
    check_readable(path);
    if (lower_extension(path) == ".ply") check_ply_structure(path);
    refuse_gltf1(path);
    Assimp::Importer imp;
    // Step 1: raw import, no post-processing, so bad input is reported before
    // anything else touches it.
    const aiScene* sc = nullptr;
    {
        const std::lock_guard<std::mutex> lock(import_mutex());
        ImportErrors errors;
        sc = imp.ReadFile(path, 0);
        if (sc)
            for (const std::string& e : errors.all) {
                if (e.find("out of range") != std::string::npos)
                    throw InputError(path + ": cannot load mesh: " + e);
                warn(path + ": " + e);
            }
    }
    if (!sc) throw InputError(load_failure(path, imp.GetErrorString()));
    check_raw(*sc, path);
    // Step 2: Triangulate splits an n-gon into n-2 triangles in place of the
    // polygon and keeps zero-area ones; JoinIdenticalVertices only renumbers
    // vertices. FindDegenerates is deliberately not run, so no triangle is
    // dropped and ids follow the file's face order within each mesh.
    sc = imp.ApplyPostProcessing(aiProcess_Triangulate | aiProcess_JoinIdenticalVertices);
    if (!sc) throw InputError(path + ": cannot load mesh: " + imp.GetErrorString());
    if (sc->mNumMaterials > std::numeric_limits<std::uint16_t>::max())
        throw InputError(path + ": more than 65535 materials");

    Mesh m;
    m.name = path;
    for (unsigned i = 0; i < sc->mNumMaterials; ++i) m.materials.push_back(to_material(*sc->mMaterials[i]));
    if (m.materials.empty()) m.materials.emplace_back();
    std::vector<std::vector<Affine>> placements(sc->mNumMeshes);
    if (sc->mRootNode) collect_placements(*sc->mRootNode, kIdentity, placements, 0, path);
    for (unsigned mi = 0; mi < sc->mNumMeshes; ++mi) {
        const aiMesh& am = *sc->mMeshes[mi];
        if (am.mMaterialIndex >= m.materials.size()) {
            std::ostringstream os;
            os << path << ": material index " << am.mMaterialIndex << " out of range in mesh " << mi;
            throw InputError(os.str());
        }
        if (placements[mi].empty()) placements[mi].push_back(kIdentity);  // in no node: where it stands
        for (const Affine& xf : placements[mi]) append_mesh(m, am, xf, path);
    }
    if (m.vertices.empty() || m.triangles.empty()) throw InputError(path + ": empty mesh (no triangles)");
    return m;
}

}  // namespace pluecker
