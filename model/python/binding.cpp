// SPDX-License-Identifier: MIT
// pybind11 module `pluecker_py`: the golden model as the cocotb benches and
// scripts see it. Every answer comes from the C++ library; Python only moves
// values around (rtl_ports and PortContract are the port contract of
// contract.hpp: the packing and every derived constant come from C++).
//
// Vectors are passed as any sequence of three numbers and returned as
// tuples. Bad arguments raise pluecker_py.InputError, a ValueError.
#include "pluecker/app/names.hpp"  // parse_fixed_mode
#include "pluecker/boxtest.hpp"
#include "pluecker/axis_contract.hpp"
#include "pluecker/contract.hpp"
#include "pluecker/f32unit.hpp"
#include "pluecker/fixed.hpp"
#include "pluecker/float_contract.hpp"
#include "pluecker/geometry.hpp"
#include "pluecker/local.hpp"
#include "pluecker/local_contract.hpp"
#include "pluecker/query.hpp"
#include "pluecker/querygen.hpp"
#include "pluecker/render.hpp"
#include "pluecker/ternary.hpp"

#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <array>
#include <cstdint>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

namespace py = pybind11;

// glm::vec3 <-> Python: any sequence of three numbers in, a tuple out.
namespace pybind11::detail {
template <>
struct type_caster<glm::vec3> {
    PYBIND11_TYPE_CASTER(glm::vec3, const_name("tuple[float, float, float]"));

    bool load(handle src, bool convert) {
        if (!src || !PySequence_Check(src.ptr()) || PyUnicode_Check(src.ptr()) || PyBytes_Check(src.ptr()))
            return false;
        const auto seq = reinterpret_borrow<sequence>(src);
        if (seq.size() != 3) return false;
        for (std::size_t a = 0; a < 3; ++a) {
            make_caster<float> c;
            if (!c.load(seq[a], convert)) return false;
            value[static_cast<int>(a)] = cast_op<float>(c);
        }
        return true;
    }

    static handle cast(const glm::vec3& v, return_value_policy, handle) {
        return py::make_tuple(v.x, v.y, v.z).release();
    }
};
}  // namespace pybind11::detail

namespace pluecker {
namespace {

using i64 = std::int64_t;

std::string vec_repr(const Vec3& v) {
    std::ostringstream s;
    s.precision(9);
    s << "(" << v.x << ", " << v.y << ", " << v.z << ")";
    return s.str();
}

template <typename T>
std::string array_repr(const std::array<T, 3>& v) {
    std::ostringstream s;
    s << "(" << v[0] << ", " << v[1] << ", " << v[2] << ")";
    return s.str();
}


// A port value (32-bit words, least significant first: contract.hpp's
// PortWords, local_contract.hpp's NodeRayWords) as a Python int, assembled
// word by word.
template <std::size_t N>
py::int_ port_int(const std::array<std::uint32_t, N>& w) {
    py::object acc = py::int_(0);
    for (std::size_t k = N; k-- > 0;) acc = (acc << py::int_(32)) | py::int_(w[k]);
    return py::int_(acc);
}

// Generated datapath operands as (FixedRay, FixedBox) tuples.
std::vector<std::pair<FixedRay, FixedBox>> operand_pairs(const std::vector<FixedQuery>& qs) {
    std::vector<std::pair<FixedRay, FixedBox>> out;
    out.reserve(qs.size());
    for (const FixedQuery& q : qs) out.emplace_back(q.ray, q.box);
    return out;
}

// The port values of one quantised query: contract.hpp's pack_query (which
// checks that every operand fits its port), as Python ints.
py::dict rtl_ports(const FixedRay& r, const FixedBox& b, const FixedFormat& f) {
    const QueryPorts p = pack_query(r, b, f);
    py::dict d;
    d["ray_class_i"] = py::int_(p.ray_class);
    d["ray_org_i"] = port_int(p.ray_org);
    d["ray_dir_i"] = port_int(p.ray_dir);
    d["ray_end_i"] = port_int(p.ray_end);
    d["ray_end_valid_i"] = py::int_(p.ray_end_valid);
    d["box_min_i"] = port_int(p.box_min);
    d["box_max_i"] = port_int(p.box_max);
    return d;
}

MulStyle mul_style_arg(const py::object& style) {
    if (py::isinstance<py::str>(style)) return parse_mul_style(style.cast<std::string>());
    if (py::isinstance<MulStyle>(style)) return style.cast<MulStyle>();
    throw InputError("mul_style must be a MulStyle or one of 'auto', 'dsp', 'lut', 'rom'");
}

PortContract make_contract(int coord_bits, int dir_bits, int tag_bits, bool conservative, const py::object& mul_style,
                           int pipeline) {
    RtlConfig c;
    c.coord_bits = coord_bits;
    c.dir_bits = dir_bits;
    c.tag_bits = tag_bits;
    c.conservative = conservative;
    c.mul_style = mul_style_arg(mul_style);
    c.pipeline = pipeline;
    return PortContract(c);
}

py::dict class_dict(const ContractClass& k) {
    py::dict d;
    d["coord_bits"] = py::make_tuple(k.coord_lo, k.coord_hi);
    d["dir_bits"] = py::make_tuple(k.dir_lo, k.dir_hi);
    d["mul_style"] = mul_style_name(k.mul_style);
    d["pipeline"] = k.pipeline;
    d["multiplier"] = k.rom ? "rom" : k.fabric ? "lut" : "dsp";
    d["mul_add"] = k.mul_add;
    d["s2x_stages"] = k.s2x_stages;
    d["latency"] = k.latency;
    d["fifo_depth"] = k.fifo_depth;
    d["mult18x18d"] = k.dsp_blocks;
    d["dp16kd"] = k.rom_blocks;
    return d;
}

FixedFormat make_format(int coord_bits, int dir_bits, const py::object& mode) {
    FixedFormat f;
    f.coord_bits = coord_bits;
    f.dir_bits = dir_bits;
    if (py::isinstance<py::str>(mode))
        f.mode = parse_fixed_mode(mode.cast<std::string>());
    else if (py::isinstance<FixedMode>(mode))
        f.mode = mode.cast<FixedMode>();
    else
        throw InputError("mode must be a FixedMode or one of 'conservative', 'nearest'");
    f.validate();
    return f;
}

// --- the local frames (local.hpp, local_contract.hpp) ------------------------

LocalFormat make_local_format(int box_bits, int dir_bits, int grid_bits, const py::object& mode) {
    LocalFormat f;
    f.box_bits = box_bits;
    f.dir_bits = dir_bits;
    f.grid_bits = grid_bits;
    if (py::isinstance<py::str>(mode))
        f.mode = parse_fixed_mode(mode.cast<std::string>());
    else if (py::isinstance<FixedMode>(mode))
        f.mode = mode.cast<FixedMode>();
    else
        throw InputError("mode must be a FixedMode or one of 'conservative', 'nearest'");
    f.validate();
    return f;
}

LocalPortContract make_local_contract(int box_bits, int dir_bits, int grid_bits, int tag_bits, bool conservative,
                                      const py::object& mul_style, int children) {
    LocalRtlConfig c;
    c.box_bits = box_bits;
    c.dir_bits = dir_bits;
    c.grid_bits = grid_bits;
    c.tag_bits = tag_bits;
    c.conservative = conservative;
    c.mul_style = mul_style_arg(mul_style);
    c.children = children;
    return LocalPortContract(c);
}

// The port values of one local query (local_contract.hpp's pack_local_query).
py::dict local_rtl_ports(const LocalRay& r, const LocalFrame& fr, const std::vector<LocalBox>& boxes,
                         const LocalPortContract& c) {
    const LocalQueryPorts p = pack_local_query(r, fr, boxes, c);
    py::dict d;
    d["ray_class_i"] = py::int_(p.ray_class);
    d["ray_org_i"] = port_int(p.ray_org);
    d["ray_dir_i"] = port_int(p.ray_dir);
    d["ray_end_i"] = port_int(p.ray_end);
    d["ray_end_valid_i"] = py::int_(p.ray_end_valid);
    d["frame_org_i"] = port_int(p.frame_org);
    d["frame_exp_i"] = py::int_(p.frame_exp);
    d["box_min_i"] = port_int(p.box_min);
    d["box_max_i"] = port_int(p.box_max);
    return d;
}

// The node ray as port values of pluecker_local_frame's outputs (suffix
// "_o") or pluecker_local_child's inputs ("_i", with the box).
py::dict node_ray_ports(const LocalNodeRay& r, const LocalFormat& f, const char* suffix) {
    const LocalNodeRayPorts p = pack_local_node_ray(r, f);
    py::dict d;
    const std::string s = suffix;
    d[py::str("cls" + s)] = py::int_(p.cls);
    d[py::str("dir" + s)] = port_int(p.dir);
    d[py::str("w" + s)] = port_int(p.w);
    d[py::str("org" + s)] = port_int(p.org);
    d[py::str("end" + s)] = port_int(p.end);
    d[py::str("end_valid" + s)] = py::int_(p.end_valid);
    return d;
}

py::dict child_ports(const LocalNodeRay& r, const LocalBox& b, const LocalFormat& f) {
    py::dict d = node_ray_ports(r, f, "_i");
    const LocalBoxPorts p = pack_local_boxes(std::span<const LocalBox>(&b, 1), f);
    d["box_min_i"] = port_int(p.box_min);
    d["box_max_i"] = port_int(p.box_max);
    return d;
}

py::dict local_class_dict(const LocalContractClass& k) {
    py::dict d;
    d["dir_bits"] = py::make_tuple(k.dir_lo, k.dir_hi);
    d["grid_bits"] = py::make_tuple(k.grid_lo, k.grid_hi);
    d["mul_style"] = mul_style_name(k.mul_style);
    d["frame_multiplier"] = k.frame_fabric ? "lut" : "dsp";
    d["child_multiplier"] = k.child_fabric ? "lut" : "dsp";
    d["frame_mul_add"] = k.frame_mul_add;
    d["child_mul_add"] = k.child_mul_add;
    d["latency"] = k.latency;
    d["fifo_depth"] = k.fifo_depth;
    d["frame_mult18x18d"] = k.frame_dsp_blocks;
    d["child_mult18x18d"] = k.child_dsp_blocks;
    return d;
}

// A software engine that also records every query it answers (the
// traversal's LocalBoxQuery stream, in the order the driver issues it).
class RecordingLocalEngine final : public LocalBoxEngine {
public:
    RecordingLocalEngine(const LocalFormat& f, std::size_t limit) : inner_(f), limit_(limit) {}
    void test(std::span<const LocalBoxQuery> batch, std::span<std::uint8_t> hits) override {
        inner_.test(batch, hits);
        for (const LocalBoxQuery& q : batch)
            if (limit_ == 0 || queries.size() < limit_) queries.push_back(q);
    }
    std::vector<LocalBoxQuery> queries;

private:
    SoftwareLocalEngine inner_;
    std::size_t limit_;
};

// The box queries of a small local-frame render (render_batched, dsa order):
// (ray, frame, box, node) tuples in issue order.
py::list local_render_queries(const std::string& scene, int size, const LocalFormat& f, std::size_t limit,
                              const std::string& frames, const std::string& cells) {
    f.validate();
    if (size < 1 || size > 4096) throw InputError("size " + std::to_string(size) + " is outside 1..4096");
    RenderOptions opts;
    opts.width = opts.height = size;
    opts.test = BoxTestKind::Local;
    opts.order = ChildOrder::Dsa;
    opts.local = f;
    if (frames != "parent" && frames != "own") throw InputError("frames must be 'parent' or 'own'");
    if (cells != "axis" && cells != "uniform") throw InputError("cells must be 'axis' or 'uniform'");
    opts.local_build.parent_origin = frames == "parent";
    opts.local_build.uniform = cells == "uniform";
    const std::unique_ptr<RenderSetup> s = make_render_setup(scene, BuildOptions{}, opts);
    RecordingLocalEngine engine(f, limit);
    RenderStats st;
    render_batched(*s->scene, s->opts, engine, st);
    py::list out;
    for (const LocalBoxQuery& q : engine.queries) out.append(py::make_tuple(q.ray, q.frame, q.box, q.node));
    return out;
}

Query make_query(const Ray& r, const Box& b) { return Query{r, b}; }

// --- binary32 units -----------------------------------------------------------

f32::Round round_arg(const std::string& name) {
    if (name == "nearest") return f32::Round::Nearest;
    if (name == "up") return f32::Round::Up;
    if (name == "down") return f32::Round::Down;
    throw InputError("round '" + name + "' is not one of nearest, up, down");
}

// A binary32 bit pattern from Python: an int in 0..2^32 - 1.
f32::Bits bits_arg(long long v, const char* what) {
    if (v < 0 || v > 0xffffffffll)
        throw InputError(std::string(what) + " = " + std::to_string(v) + " is not a 32-bit pattern (0..2^32 - 1)");
    return static_cast<f32::Bits>(v);
}

std::array<f32::Bits, 3> bits3_arg(const std::array<long long, 3>& v, const char* what) {
    return {bits_arg(v[0], what), bits_arg(v[1], what), bits_arg(v[2], what)};
}

RayClass class_arg(int c) {
    if (c < 0 || c > 7) throw InputError("ray class " + std::to_string(c) + " is outside 0..7");
    return static_cast<RayClass>(c);
}

// The input port values of a float unit's query (float_contract.hpp), as
// Python ints.
py::dict float_ports(const std::vector<FloatPortValue>& values) {
    py::dict d;
    for (const FloatPortValue& v : values) d[py::str(v.name)] = port_int(v.value);
    return d;
}

std::string hex3(const std::array<f32::Bits, 3>& v) {
    std::ostringstream s;
    s << std::hex << "(0x" << v[0] << ", 0x" << v[1] << ", 0x" << v[2] << ")";
    return s.str();
}

FloatRtlConfig make_float_config(const std::string& unit, int tag_bits, bool conservative, int mul_dsp) {
    FloatRtlConfig c;
    c.unit = parse_float_unit(unit);
    c.tag_bits = tag_bits;
    c.conservative = conservative;
    c.mul_dsp = mul_dsp;
    return c;
}

// Setter of FixedFormat.coord_bits / dir_bits: a width outside
// MIN_BITS..MAX_BITS would reach shifts by a negative or too large count
// (undefined behaviour) in the fixed-point code, so it is refused here and
// the format keeps its old value.
auto width_setter(int FixedFormat::*field, const char* name) {
    return [field, name](FixedFormat& f, int bits) {
        if (bits < FixedFormat::kMinBits || bits > FixedFormat::kMaxBits)
            throw InputError(std::string("FixedFormat.") + name + " = " + std::to_string(bits) + " is outside " +
                             std::to_string(FixedFormat::kMinBits) + ".." + std::to_string(FixedFormat::kMaxBits));
        f.*field = bits;
    };
}

}  // namespace
}  // namespace pluecker

PYBIND11_MODULE(pluecker_py, m) {
    using namespace pluecker;
    m.doc() = "Golden model of the fixed-point Pluecker ray/box intersector";

    py::register_exception<InputError>(m, "InputError", PyExc_ValueError);

    // --- float geometry --------------------------------------------------
    py::class_<Ray>(m, "Ray", "Ray o + t*d, 0 <= t <= tmax (tmax = inf: unbounded)")
        .def(py::init([](const Vec3& o, const Vec3& d, float tmax) { return Ray{o, d, tmax}; }), py::arg("o"),
             py::arg("d"), py::arg("tmax") = kInf)
        .def_readwrite("o", &Ray::o)
        .def_readwrite("d", &Ray::d)
        .def_readwrite("tmax", &Ray::tmax)
        .def("__repr__", [](const Ray& r) {
            return "Ray(o=" + vec_repr(r.o) + ", d=" + vec_repr(r.d) + ", tmax=" + std::to_string(r.tmax) + ")";
        });

    py::class_<Box>(m, "Box", "Closed axis-aligned box [lo, hi]")
        .def(py::init([](const Vec3& lo, const Vec3& hi) { return Box{lo, hi}; }), py::arg("lo"), py::arg("hi"))
        .def_readwrite("lo", &Box::lo)
        .def_readwrite("hi", &Box::hi)
        .def("empty", &Box::empty)
        .def("__repr__", [](const Box& b) { return "Box(lo=" + vec_repr(b.lo) + ", hi=" + vec_repr(b.hi) + ")"; });

    py::class_<Query>(m, "Query", "One ray/box query")
        .def(py::init(&make_query), py::arg("ray"), py::arg("box"))
        .def_readwrite("ray", &Query::ray)
        .def_readwrite("box", &Query::box)
        .def("line", [](const Query& q) {
            std::ostringstream s;
            write_query(s, q);
            std::string line = s.str();
            while (!line.empty() && line.back() == '\n') line.pop_back();
            return line;
        }, "The query as one line of the query text format (hex floats, exact)")
        .def("__repr__", [](const Query& q) {
            return "Query(o=" + vec_repr(q.ray.o) + ", d=" + vec_repr(q.ray.d) + ", tmax=" +
                   std::to_string(q.ray.tmax) + ", lo=" + vec_repr(q.box.lo) + ", hi=" + vec_repr(q.box.hi) + ")";
        });

    m.def("ray_class", &ray_class, py::arg("d"), "Ray class: bit a set when d[a] has its sign bit set");
    m.def("class_name", [](int c) {
        return class_name(class_arg(c));
    }, py::arg("cls"));

    // --- query files and generators --------------------------------------
    m.def("read_queries_file", &read_queries_file, py::arg("path"),
          "Read a query file (13 numbers a line); raises InputError naming file:line");
    m.def("read_queries_text", [](const std::string& text, const std::string& source) {
        std::istringstream in(text);
        return read_queries(in, source);
    }, py::arg("text"), py::arg("source") = "<text>");
    m.def("validate_query", [](const Query& q, const std::string& where) { validate_query(q, where); },
          py::arg("query"), py::arg("where") = "query");
    m.def("random_queries", [](std::uint64_t seed, std::size_t n) { return random_queries(seed, n); },
          py::arg("seed"), py::arg("n"));
    m.def("extreme_queries", [](std::uint64_t seed, std::size_t n) { return extreme_queries(seed, n); },
          py::arg("seed"), py::arg("n"));
    m.def("extreme_query_families", [](std::uint64_t seed, std::size_t n) {
        std::vector<std::size_t> fam;
        extreme_queries(seed, n, &fam);
        return fam;
    }, py::arg("seed"), py::arg("n"), "Family index of every query extreme_queries(seed, n) returns");
    m.def("setup_queries", [](std::uint64_t seed, std::size_t n, int coord_bits) {
        return setup_queries(seed, n, coord_bits);
    }, py::arg("seed"), py::arg("n"), py::arg("coord_bits"),
          "Rays from anywhere into boxes of the range of coord_bits (querygen.hpp's set-up families)");
    m.def("setup_family_count", &setup_family_count);
    m.def("setup_family_name", &setup_family_name, py::arg("family"));
    m.def("extreme_family_count", &extreme_family_count);
    m.def("extreme_family_name", &extreme_family_name, py::arg("family"));
    // Datapath operands (querygen.hpp): lists of (FixedRay, FixedBox).
    m.def("port_range_queries", [](std::uint64_t seed, std::size_t n, const FixedFormat& f) {
        return operand_pairs(port_range_queries(seed, n, f));
    }, py::arg("seed"), py::arg("n"), py::arg("fmt"),
          "Operands from the full port ranges of fmt (any C-bit coordinates, D-bit directions, LO > HI boxes)");
    m.def("boundary_queries", [](std::uint64_t seed, std::size_t n, const FixedFormat& f) {
        return operand_pairs(boundary_queries(seed, n, f));
    }, py::arg("seed"), py::arg("n"), py::arg("fmt"),
          "Operands exactly on a decision boundary of one test of the datapath (edge, end, origin)");
    m.def("boundary_query_kinds", [](std::uint64_t seed, std::size_t n, const FixedFormat& f) {
        std::vector<std::size_t> kinds;
        boundary_queries(seed, n, f, &kinds);
        return kinds;
    }, py::arg("seed"), py::arg("n"), py::arg("fmt"), "Kind index of every query boundary_queries returns");
    m.def("boundary_kind_name", &boundary_kind_name, py::arg("kind"));

    // --- float tests -------------------------------------------------------
    m.def("exact_hit", [](const Ray& r, const Box& b) {
        validate_query(Query{r, b}, "exact_hit");
        return exact_hit(r, b);
    }, py::arg("ray"), py::arg("box"), "Ground truth in exact rational arithmetic");
    m.def("smits_hit", [](const Ray& r, const Box& b) {
        validate_query(Query{r, b}, "smits_hit");
        return smits_hit(smits_setup(r), b);
    }, py::arg("ray"), py::arg("box"), "Float slab test 'smits-mul-cls'");
    m.def("pluecker_hit", [](const Ray& r, const Box& b) {
        validate_query(Query{r, b}, "pluecker_hit");
        return pluecker_hit(pluecker_setup(r), b);
    }, py::arg("ray"), py::arg("box"), "Float Pluecker test 'pluecker-cls'");

    m.def("exact_hit", [](const Query& q) {
        validate_query(q, "exact_hit");
        return exact_hit(q.ray, q.box);
    }, py::arg("query"));
    m.def("smits_hit", [](const Query& q) {
        validate_query(q, "smits_hit");
        return smits_hit(smits_setup(q.ray), q.box);
    }, py::arg("query"));
    m.def("pluecker_hit", [](const Query& q) {
        validate_query(q, "pluecker_hit");
        return pluecker_hit(pluecker_setup(q.ray), q.box);
    }, py::arg("query"));

    // --- fixed point -------------------------------------------------------
    py::enum_<FixedMode>(m, "FixedMode")
        .value("Conservative", FixedMode::Conservative)
        .value("Nearest", FixedMode::Nearest);
    m.def("parse_fixed_mode", &parse_fixed_mode, py::arg("name"));
    m.def("mode_name", &mode_name, py::arg("mode"));

    py::class_<FixedFormat>(m, "FixedFormat", "Fixed-point format: widths and rounding mode (see fixed.hpp)")
        .def(py::init(&make_format), py::arg("coord_bits") = FixedFormat::kDefaultCoordBits,
             py::arg("dir_bits") = FixedFormat::kDefaultDirBits, py::arg("mode") = FixedMode::Conservative)
        .def_property("coord_bits", [](const FixedFormat& f) { return f.coord_bits; },
                      width_setter(&FixedFormat::coord_bits, "coord_bits"))
        .def_property("dir_bits", [](const FixedFormat& f) { return f.dir_bits; },
                      width_setter(&FixedFormat::dir_bits, "dir_bits"))
        .def_readwrite("mode", &FixedFormat::mode)
        .def_readonly_static("MIN_BITS", &FixedFormat::kMinBits)
        .def_readonly_static("MAX_BITS", &FixedFormat::kMaxBits)
        .def("validate", &FixedFormat::validate)
        .def("coord_min", &FixedFormat::coord_min)
        .def("coord_max", &FixedFormat::coord_max)
        .def("dir_one", &FixedFormat::dir_one)
        .def("coord_lsb", &FixedFormat::coord_lsb)
        .def("dir_lsb", &FixedFormat::dir_lsb)
        .def("coord_lo_value", &FixedFormat::coord_lo_value)
        .def("coord_hi_value", &FixedFormat::coord_hi_value)
        .def("range_box", &FixedFormat::range_box, "The range cube R: every box the datapath takes lies in it")
        .def("range_text", &FixedFormat::range_text)
        .def("__repr__", [](const FixedFormat& f) {
            return "FixedFormat(coord_bits=" + std::to_string(f.coord_bits) + ", dir_bits=" +
                   std::to_string(f.dir_bits) + ", mode='" + mode_name(f.mode) + "')";
        });

    py::class_<FixedRay>(m, "FixedRay", "Quantised ray as the RTL receives it")
        .def(py::init([](int cls, const std::array<i64, 3>& org, const std::array<i64, 3>& dir,
                         const std::array<i64, 3>& end, bool has_end) {
                 FixedRay r;
                 r.cls = class_arg(cls);
                 r.org = org;
                 r.dir = dir;
                 r.end = end;
                 r.has_end = has_end;
                 return r;
             }),
             py::arg("cls") = 0, py::arg("org") = std::array<i64, 3>{}, py::arg("dir") = std::array<i64, 3>{},
             py::arg("end") = std::array<i64, 3>{}, py::arg("has_end") = false)
        .def_property("cls", [](const FixedRay& r) { return static_cast<int>(r.cls); },
                      [](FixedRay& r, int c) {
                          r.cls = class_arg(c);
                      })
        .def_readwrite("org", &FixedRay::org)
        .def_readwrite("dir", &FixedRay::dir)
        .def_readwrite("end", &FixedRay::end)
        .def_readwrite("has_end", &FixedRay::has_end)
        .def_readwrite("clipped", &FixedRay::clipped)
        .def("__repr__", [](const FixedRay& r) {
            return "FixedRay(cls=" + std::to_string(r.cls) + ", org=" + array_repr(r.org) + ", dir=" +
                   array_repr(r.dir) + ", end=" + array_repr(r.end) + ", has_end=" + (r.has_end ? "True" : "False") +
                   ")";
        });

    py::class_<FixedBox>(m, "FixedBox", "Quantised box as the RTL receives it")
        .def(py::init([](const std::array<i64, 3>& lo, const std::array<i64, 3>& hi) { return FixedBox{lo, hi}; }),
             py::arg("lo") = std::array<i64, 3>{}, py::arg("hi") = std::array<i64, 3>{})
        .def_readwrite("lo", &FixedBox::lo)
        .def_readwrite("hi", &FixedBox::hi)
        .def("__repr__",
             [](const FixedBox& b) { return "FixedBox(lo=" + array_repr(b.lo) + ", hi=" + array_repr(b.hi) + ")"; });

    m.def("fixed_setup_ray", &fixed_setup_ray, py::arg("ray"), py::arg("fmt"),
          "The ray as the RTL receives it (any finite origin: one outside the range cube is clipped "
          "exactly onto it), or None when the segment never meets the range cube (a miss)");
    m.def("fixed_setup_end", [](FixedRay r, const Ray& ray, const FixedFormat& f) {
        f.validate();
        fixed_setup_end(r, ray, f);
        return r;
    }, py::arg("fixed_ray"), py::arg("ray"), py::arg("fmt"),
          "A copy of fixed_ray with the segment end recomputed from ray (same o and d, new tmax)");
    m.def("fixed_quantize_box", &fixed_quantize_box, py::arg("box"), py::arg("fmt"));
    m.def("fixed_hit", [](const FixedRay& r, const FixedBox& b, const FixedFormat& f) {
        check_query_operands(r, b, f);
        return fixed_hit(r, b, f);
    }, py::arg("ray"), py::arg("box"), py::arg("fmt"), "The bit-exact datapath on quantised operands");
    m.def("fixed_hit", [](const Ray& r, const Box& b, const FixedFormat& f) {
        return fixed_hit(r, b, f);
    }, py::arg("ray"), py::arg("box"), py::arg("fmt"), "Set up and test one float query");
    m.def("fixed_hit", [](const Query& q, const FixedFormat& f) {
        return fixed_hit(q.ray, q.box, f);
    }, py::arg("query"), py::arg("fmt"), "Set up and test one float query");
    // --- ternary answers (ternary.hpp) -------------------------------------
    py::enum_<TernaryAnswer>(m, "TernaryAnswer")
        .value("Miss", TernaryAnswer::Miss)
        .value("Uncertain", TernaryAnswer::Uncertain)
        .value("Hit", TernaryAnswer::Hit);
    m.def("fixed_strict_hit", [](const FixedRay& r, const FixedBox& b, const FixedFormat& f) {
        check_query_operands(r, b, f);
        return fixed_strict_hit(r, b, f);
    }, py::arg("ray"), py::arg("box"), py::arg("fmt"),
          "The strict test alone (out_strict_o of a TERNARY unit); conservative formats only");
    m.def("fixed_ternary", [](const FixedRay& r, const FixedBox& b, const FixedFormat& f) {
        check_query_operands(r, b, f);
        return fixed_ternary(r, b, f);
    }, py::arg("ray"), py::arg("box"), py::arg("fmt"),
          "Certain miss, certain hit or uncertain (out_hit_o, out_strict_o); conservative formats only");
    m.def("fixed_ternary", [](const Ray& r, const Box& b, const FixedFormat& f) {
        return fixed_ternary(r, b, f);
    }, py::arg("ray"), py::arg("box"), py::arg("fmt"), "Set up and answer one float query");
    m.def("rtl_ports", &rtl_ports, py::arg("ray"), py::arg("box"), py::arg("fmt"),
          "Port values of rtl/pluecker_intersector.sv for one quantised query: a dict from port name "
          "(ray_class_i, ray_org_i, ray_dir_i, ray_end_i, ray_end_valid_i, box_min_i, box_max_i) to an "
          "unsigned int; x in the low field, two's complement coordinates (the port contract's packing)");

    // --- the port contract (contract.hpp) ----------------------------------
    py::enum_<MulStyle>(m, "MulStyle")
        .value("Auto", MulStyle::Auto)
        .value("Dsp", MulStyle::Dsp)
        .value("Lut", MulStyle::Lut)
        .value("Rom", MulStyle::Rom);
    m.def("parse_mul_style", &parse_mul_style, py::arg("name"));
    m.def("mul_style_name", &mul_style_name, py::arg("style"));

    py::enum_<PortDir>(m, "PortDir").value("In", PortDir::In).value("Out", PortDir::Out);
    py::class_<PortSpec>(m, "PortSpec", "One port of rtl/pluecker_intersector.sv")
        .def_readonly("name", &PortSpec::name)
        .def_readonly("dir", &PortSpec::dir)
        .def_readonly("fields", &PortSpec::fields)
        .def_readonly("field_bits", &PortSpec::field_bits)
        .def_readonly("is_signed", &PortSpec::is_signed)
        .def_property_readonly("width", &PortSpec::width)
        .def("field_lsb", &PortSpec::field_lsb, py::arg("field"), "Lowest bit of field 0 (x), 1 (y) or 2 (z)")
        .def("__repr__", [](const PortSpec& p) {
            return "PortSpec(" + p.name + ", " + (p.dir == PortDir::In ? "in" : "out") + ", " +
                   std::to_string(p.fields) + " x " + std::to_string(p.field_bits) + (p.is_signed ? ", signed" : "") +
                   ")";
        });

    py::class_<PortContract>(m, "PortContract",
                             "The port contract of rtl/pluecker_intersector.sv for one configuration: the "
                             "constants the RTL derives from its parameters and its ports (contract.hpp)")
        .def(py::init(&make_contract), py::arg("coord_bits") = ContractDefaults::kCoordBits,
             py::arg("dir_bits") = ContractDefaults::kDirBits, py::arg("tag_bits") = ContractDefaults::kTagBits,
             py::arg("conservative") = true, py::arg("mul_style") = "auto", py::arg("pipeline") = 0)
        .def_property_readonly("coord_bits", [](const PortContract& c) { return c.config().coord_bits; })
        .def_property_readonly("dir_bits", [](const PortContract& c) { return c.config().dir_bits; })
        .def_property_readonly("tag_bits", [](const PortContract& c) { return c.config().tag_bits; })
        .def_property_readonly("conservative", [](const PortContract& c) { return c.config().conservative; })
        .def_property_readonly("mul_style", [](const PortContract& c) { return c.config().mul_style; })
        .def_property_readonly("pipeline", [](const PortContract& c) { return c.config().pipeline; })
        .def_property_readonly("format", &PortContract::format, "The FixedFormat of the configuration")
        .def_property_readonly("mul_a_bits", &PortContract::mul_a_bits, "WA = COORD_BITS + 1")
        .def_property_readonly("mul_b_bits", &PortContract::mul_b_bits, "WB = DIR_BITS + 1")
        .def_property_readonly("fabric_multipliers", &PortContract::fabric_multipliers)
        .def_property_readonly("mul_add", &PortContract::mul_add)
        .def_property_readonly("s2x_stages", &PortContract::s2x_stages)
        .def_property_readonly("latency", &PortContract::latency)
        .def_property_readonly("fifo_depth", &PortContract::fifo_depth)
        .def_property_readonly("dsp_blocks", &PortContract::dsp_blocks, "MULT18X18D of one intersector")
        .def_property_readonly("rom_multipliers", &PortContract::rom_multipliers, "MUL_STYLE rom (pluecker_mul_rom)")
        .def_property_readonly("rom_blocks", &PortContract::rom_blocks, "DP16KD of one intersector's multipliers")
        .def_property_readonly("ports", &PortContract::ports)
        .def("port", &PortContract::port, py::arg("name"), py::return_value_policy::copy)
        .def("rtl_ports", [](const PortContract& c, const FixedRay& r, const FixedBox& b) {
            return rtl_ports(r, b, c.format());
        }, py::arg("ray"), py::arg("box"), "rtl_ports(ray, box, self.format)")
        .def_property_readonly("axis_tdata_fields", [](const PortContract& c) {
            py::list out;
            for (const TdataField& f : axis_tdata_fields(c)) out.append(py::make_tuple(f.port, f.lsb, f.width));
            return out;
        }, "(port, lsb, width) of each input port in the AXI4-Stream wrapper's s_axis_tdata_i (axis_contract.hpp)")
        .def_property_readonly("axis_query_bits", &axis_query_bits, "The bits of the tdata fields together")
        .def_property_readonly("axis_tdata_bits", &axis_tdata_bits, "s_axis_tdata_i's width (whole bytes)")
        .def_readonly_static("MIN_BITS", &ContractLimits::kMinBits)
        .def_readonly_static("MAX_BITS", &ContractLimits::kMaxBits)
        .def_readonly_static("MIN_TAG_BITS", &ContractLimits::kMinTagBits)
        .def_readonly_static("MAX_PIPELINE", &ContractLimits::kMaxPipeline)
        .def("__repr__", [](const PortContract& c) {
            const RtlConfig& k = c.config();
            return "PortContract(coord_bits=" + std::to_string(k.coord_bits) + ", dir_bits=" +
                   std::to_string(k.dir_bits) + ", tag_bits=" + std::to_string(k.tag_bits) + ", conservative=" +
                   (k.conservative ? "True" : "False") + ", mul_style='" + mul_style_name(k.mul_style) +
                   "', pipeline=" + std::to_string(k.pipeline) + "): LATENCY " + std::to_string(c.latency()) +
                   ", FIFO_DEPTH " + std::to_string(c.fifo_depth());
        });
    // --- binary32 units (f32unit.hpp, float_contract.hpp) ----------------------
    m.def("f32_add", [](long long a, long long b, const std::string& r) {
        return f32::add(bits_arg(a, "a"), bits_arg(b, "b"), round_arg(r));
    }, py::arg("a"), py::arg("b"), py::arg("round") = "nearest", "pluecker_f32_add (SUB = 0) on bit patterns");
    m.def("f32_sub", [](long long a, long long b, const std::string& r) {
        return f32::sub(bits_arg(a, "a"), bits_arg(b, "b"), round_arg(r));
    }, py::arg("a"), py::arg("b"), py::arg("round") = "nearest", "pluecker_f32_add (SUB = 1) on bit patterns");
    m.def("f32_mul", [](long long a, long long b, const std::string& r) {
        return f32::mul(bits_arg(a, "a"), bits_arg(b, "b"), round_arg(r));
    }, py::arg("a"), py::arg("b"), py::arg("round") = "nearest", "pluecker_f32_mul on bit patterns");
    m.def("f32_lt", [](long long a, long long b) { return f32::lt(bits_arg(a, "a"), bits_arg(b, "b")); },
          py::arg("a"), py::arg("b"));
    m.def("f32_le", [](long long a, long long b) { return f32::le(bits_arg(a, "a"), bits_arg(b, "b")); },
          py::arg("a"), py::arg("b"));
    m.def("f32_bits", &f32::bits_of, py::arg("x"), "The binary32 bit pattern of a float");
    m.def("f32_value", [](long long b) { return f32::float_of(bits_arg(b, "bits")); }, py::arg("bits"));

    py::class_<F32PlueckerQuery>(m, "F32PlueckerQuery",
                                 "A query of rtl/pluecker_float_intersector.sv: binary32 bit patterns")
        .def(py::init([](int cls, const std::array<long long, 3>& org, const std::array<long long, 3>& dir,
                         const std::array<long long, 3>& end, bool has_end, const std::array<long long, 3>& lo,
                         const std::array<long long, 3>& hi) {
                 F32PlueckerQuery q;
                 q.cls = class_arg(cls);
                 q.org = bits3_arg(org, "org");
                 q.dir = bits3_arg(dir, "dir");
                 q.end = bits3_arg(end, "end");
                 q.has_end = has_end;
                 q.lo = bits3_arg(lo, "lo");
                 q.hi = bits3_arg(hi, "hi");
                 return q;
             }),
             py::arg("cls"), py::arg("org"), py::arg("dir"), py::arg("end"), py::arg("has_end"), py::arg("lo"),
             py::arg("hi"))
        .def_property_readonly("cls", [](const F32PlueckerQuery& q) { return static_cast<int>(q.cls); })
        .def_readonly("org", &F32PlueckerQuery::org)
        .def_readonly("dir", &F32PlueckerQuery::dir)
        .def_readonly("end", &F32PlueckerQuery::end)
        .def_readonly("has_end", &F32PlueckerQuery::has_end)
        .def_readonly("lo", &F32PlueckerQuery::lo)
        .def_readonly("hi", &F32PlueckerQuery::hi)
        .def("ports", [](const F32PlueckerQuery& q) { return float_ports(pack_float_query(q)); },
             "Input port values (the port contract's packing, float_contract.hpp)")
        .def("__repr__", [](const F32PlueckerQuery& q) {
            return "F32PlueckerQuery(cls=" + std::to_string(q.cls) + ", org=" + hex3(q.org) + ", dir=" + hex3(q.dir) +
                   ", end=" + hex3(q.end) + ", has_end=" + (q.has_end ? "True" : "False") + ", lo=" + hex3(q.lo) +
                   ", hi=" + hex3(q.hi) + ")";
        });
    m.def("f32_pluecker_query", [](const Query& q, bool conservative) {
        validate_query(q, "f32_pluecker_query");
        return f32_pluecker_query(q.ray, q.box, conservative);
    }, py::arg("query"), py::arg("conservative") = false,
          "The ray set-up of the Plücker float unit (pluecker_setup; conservative: the end rounded outward)");
    m.def("f32_pluecker_hit", py::overload_cast<const F32PlueckerQuery&, bool>(&f32_pluecker_hit), py::arg("query"),
          py::arg("conservative") = false, "The Plücker float unit's answer, bit for bit the RTL's");

    py::class_<F32SmitsQuery>(m, "F32SmitsQuery", "A query of rtl/pluecker_smits_intersector.sv: bit patterns")
        .def(py::init([](int cls, const std::array<long long, 3>& org, const std::array<long long, 3>& inv,
                         long long tmax, const std::array<long long, 3>& lo, const std::array<long long, 3>& hi) {
                 F32SmitsQuery q;
                 q.cls = class_arg(cls);
                 q.org = bits3_arg(org, "org");
                 q.inv = bits3_arg(inv, "inv");
                 q.tmax = bits_arg(tmax, "tmax");
                 q.lo = bits3_arg(lo, "lo");
                 q.hi = bits3_arg(hi, "hi");
                 return q;
             }),
             py::arg("cls"), py::arg("org"), py::arg("inv"), py::arg("tmax"), py::arg("lo"), py::arg("hi"))
        .def_property_readonly("cls", [](const F32SmitsQuery& q) { return static_cast<int>(q.cls); })
        .def_readonly("org", &F32SmitsQuery::org)
        .def_readonly("inv", &F32SmitsQuery::inv)
        .def_readonly("tmax", &F32SmitsQuery::tmax)
        .def_readonly("lo", &F32SmitsQuery::lo)
        .def_readonly("hi", &F32SmitsQuery::hi)
        .def("ports", [](const F32SmitsQuery& q) { return float_ports(pack_float_query(q)); },
             "Input port values (the port contract's packing, float_contract.hpp)")
        .def("__repr__", [](const F32SmitsQuery& q) {
            std::ostringstream t;
            t << std::hex << "0x" << q.tmax;
            return "F32SmitsQuery(cls=" + std::to_string(q.cls) + ", org=" + hex3(q.org) + ", inv=" + hex3(q.inv) +
                   ", tmax=" + t.str() + ", lo=" + hex3(q.lo) + ", hi=" + hex3(q.hi) + ")";
        });
    m.def("f32_smits_query", [](const Query& q) {
        validate_query(q, "f32_smits_query");
        return f32_smits_query(q.ray, q.box);
    }, py::arg("query"), "The ray set-up of the slab float unit (smits_setup: inv = 1/d in host float)");
    m.def("f32_smits_hit", py::overload_cast<const F32SmitsQuery&>(&f32_smits_hit), py::arg("query"),
          "The slab float unit's answer, bit for bit the RTL's");

    py::class_<FloatPortContract>(m, "FloatPortContract",
                                  "The port contract of a binary32 unit (float_contract.hpp): 'float' is "
                                  "rtl/pluecker_float_intersector.sv, 'smits' rtl/pluecker_smits_intersector.sv")
        .def(py::init([](const std::string& unit, int tag_bits, bool conservative, int mul_dsp) {
                 return FloatPortContract(make_float_config(unit, tag_bits, conservative, mul_dsp));
             }),
             py::arg("unit"), py::arg("tag_bits") = ContractDefaults::kTagBits, py::arg("conservative") = false,
             py::arg("mul_dsp") = FloatLimits::kDefaultMulDsp)
        .def_property_readonly("unit", [](const FloatPortContract& c) { return float_unit_name(c.config().unit); })
        .def_property_readonly("module", &FloatPortContract::module)
        .def_property_readonly("tag_bits", [](const FloatPortContract& c) { return c.config().tag_bits; })
        .def_property_readonly("conservative", [](const FloatPortContract& c) { return c.config().conservative; })
        .def_property_readonly("mul_dsp", [](const FloatPortContract& c) { return c.config().mul_dsp; })
        .def_property_readonly("adders", &FloatPortContract::adders)
        .def_property_readonly("multipliers", &FloatPortContract::multipliers)
        .def_property_readonly("latency", &FloatPortContract::latency)
        .def_property_readonly("fifo_depth", &FloatPortContract::fifo_depth)
        .def_property_readonly("dsp_blocks", &FloatPortContract::dsp_blocks)
        .def_property_readonly("ports", &FloatPortContract::ports)
        .def("port", &FloatPortContract::port, py::arg("name"), py::return_value_policy::copy)
        .def_readonly_static("ADD_LATENCY", &FloatLimits::kAddLatency)
        .def_readonly_static("MUL_LATENCY", &FloatLimits::kMulLatency)
        .def_readonly_static("DEFAULT_MUL_DSP", &FloatLimits::kDefaultMulDsp)
        .def("__repr__", [](const FloatPortContract& c) {
            return std::string("FloatPortContract(") + float_unit_name(c.config().unit) +
                   ", tag_bits=" + std::to_string(c.config().tag_bits) +
                   ", conservative=" + (c.config().conservative ? "True" : "False") +
                   ", mul_dsp=" + std::to_string(c.config().mul_dsp) + "): LATENCY " + std::to_string(c.latency()) +
                   ", FIFO_DEPTH " + std::to_string(c.fifo_depth());
        });

    m.def("contract_classes", [] {
        py::list out;
        for (const ContractClass& k : contract_classes()) out.append(class_dict(k));
        return out;
    }, "The configuration classes of the port contract (as rtl/pluecker_contract.json lists them)");

    // --- local frames (local.hpp) and the local unit's port contract -------
    py::class_<LocalFormat>(m, "LocalFormat", "Local-frame format: K, D, G and the rounding mode (see local.hpp)")
        .def(py::init(&make_local_format), py::arg("box_bits") = LocalContractDefaults::kBoxBits,
             py::arg("dir_bits") = LocalContractDefaults::kDirBits,
             py::arg("grid_bits") = LocalContractDefaults::kGridBits, py::arg("mode") = FixedMode::Conservative)
        .def_readonly("box_bits", &LocalFormat::box_bits)
        .def_readonly("dir_bits", &LocalFormat::dir_bits)
        .def_readonly("grid_bits", &LocalFormat::grid_bits)
        .def_readonly("mode", &LocalFormat::mode)
        .def("validate", &LocalFormat::validate)
        .def("box_max", &LocalFormat::box_max)
        .def("max_exp", &LocalFormat::max_exp)
        .def("w_max", &LocalFormat::w_max)
        .def("w_min", &LocalFormat::w_min)
        .def("grid_min", &LocalFormat::grid_min)
        .def("grid_max", &LocalFormat::grid_max)
        .def("range_box", &LocalFormat::range_box)
        .def("range_text", &LocalFormat::range_text)
        .def("__repr__", [](const LocalFormat& f) {
            return "LocalFormat(box_bits=" + std::to_string(f.box_bits) + ", dir_bits=" + std::to_string(f.dir_bits) +
                   ", grid_bits=" + std::to_string(f.grid_bits) + ", mode='" + mode_name(f.mode) + "')";
        });

    py::class_<LocalRay>(m, "LocalRay", "A ray at the global width G, as local_setup_ray gives it")
        .def(py::init([](int cls, const std::array<i64, 3>& org, const std::array<i64, 3>& dir_g,
                         const std::array<i64, 3>& end, bool has_end) {
                 LocalRay r;
                 r.cls = class_arg(cls);
                 r.org = org;
                 r.dir_g = dir_g;
                 r.end = end;
                 r.has_end = has_end;
                 return r;
             }),
             py::arg("cls") = 0, py::arg("org") = std::array<i64, 3>{}, py::arg("dir_g") = std::array<i64, 3>{},
             py::arg("end") = std::array<i64, 3>{}, py::arg("has_end") = false)
        .def_property_readonly("cls", [](const LocalRay& r) { return static_cast<int>(r.cls); })
        .def_readonly("org", &LocalRay::org)
        .def_readonly("dir_g", &LocalRay::dir_g)
        .def_readonly("end", &LocalRay::end)
        .def_readonly("has_end", &LocalRay::has_end)
        .def_readonly("clipped", &LocalRay::clipped)
        .def("__eq__", [](const LocalRay& a, const LocalRay& b) {
            return a.cls == b.cls && a.org == b.org && a.dir_g == b.dir_g && a.end == b.end && a.has_end == b.has_end;
        })
        .def("__repr__", [](const LocalRay& r) {
            return "LocalRay(cls=" + std::to_string(r.cls) + ", org=" + array_repr(r.org) + ", dir_g=" +
                   array_repr(r.dir_g) + ", end=" + array_repr(r.end) + ", has_end=" + (r.has_end ? "True" : "False") +
                   ")";
        });

    py::class_<LocalFrame>(m, "LocalFrame", "A node's frame: origin on the grid, cell 2^exp grid units per axis")
        .def(py::init([](const std::array<i64, 3>& origin, const std::array<int, 3>& exp) {
                 return LocalFrame{origin, exp};
             }),
             py::arg("origin") = std::array<i64, 3>{}, py::arg("exp") = std::array<int, 3>{})
        .def_readonly("origin", &LocalFrame::origin)
        .def_readonly("exp", &LocalFrame::exp)
        .def("__eq__", [](const LocalFrame& a, const LocalFrame& b) { return a == b; })
        .def("__repr__", [](const LocalFrame& f) {
            return "LocalFrame(origin=" + array_repr(f.origin) + ", exp=" + array_repr(f.exp) + ")";
        });

    py::class_<LocalBox>(m, "LocalBox", "A box as K-bit offsets in a frame")
        .def(py::init([](const std::array<i64, 3>& lo, const std::array<i64, 3>& hi) { return LocalBox{lo, hi}; }),
             py::arg("lo") = std::array<i64, 3>{}, py::arg("hi") = std::array<i64, 3>{})
        .def_readonly("lo", &LocalBox::lo)
        .def_readonly("hi", &LocalBox::hi)
        .def("__eq__", [](const LocalBox& a, const LocalBox& b) { return a == b; })
        .def("__repr__",
             [](const LocalBox& b) { return "LocalBox(lo=" + array_repr(b.lo) + ", hi=" + array_repr(b.hi) + ")"; });

    py::class_<LocalNodeRay>(m, "LocalNodeRay", "The ray in one node's frame: the child datapath's ray operands")
        .def(py::init([](int cls, const std::array<i64, 3>& dir, const std::array<i64, 6>& w,
                         const std::array<i64, 3>& org, const std::array<i64, 3>& end, bool has_end) {
                 LocalNodeRay r;
                 r.cls = class_arg(cls);
                 r.dir = dir;
                 r.w = w;
                 r.org = org;
                 r.end = end;
                 r.has_end = has_end;
                 return r;
             }),
             py::arg("cls") = 0, py::arg("dir") = std::array<i64, 3>{}, py::arg("w") = std::array<i64, 6>{},
             py::arg("org") = std::array<i64, 3>{}, py::arg("end") = std::array<i64, 3>{},
             py::arg("has_end") = false)
        .def_property_readonly("cls", [](const LocalNodeRay& r) { return static_cast<int>(r.cls); })
        .def_readonly("dir", &LocalNodeRay::dir)
        .def_readonly("w", &LocalNodeRay::w)
        .def_readonly("org", &LocalNodeRay::org)
        .def_readonly("end", &LocalNodeRay::end)
        .def_readonly("has_end", &LocalNodeRay::has_end)
        .def("__eq__", [](const LocalNodeRay& a, const LocalNodeRay& b) { return a == b; })
        .def("__repr__", [](const LocalNodeRay& r) {
            std::ostringstream s;
            s << "LocalNodeRay(cls=" << static_cast<int>(r.cls) << ", dir=" << array_repr(r.dir) << ", w=(";
            for (std::size_t k = 0; k < r.w.size(); ++k) s << (k ? ", " : "") << r.w[k];
            s << "), org=" << array_repr(r.org) << ", end=" << array_repr(r.end)
              << ", has_end=" << (r.has_end ? "True" : "False") << ")";
            return s.str();
        });

    m.def("local_setup_ray", &local_setup_ray, py::arg("ray"), py::arg("fmt"),
          "The ray at the global width (any finite origin: one outside the grid's range is clipped exactly "
          "onto it), or None when the segment never meets the range");
    m.def("local_setup_end", [](LocalRay r, const Ray& ray, const LocalFormat& f) {
        f.validate();
        local_setup_end(r, ray, f);
        return r;
    }, py::arg("local_ray"), py::arg("ray"), py::arg("fmt"),
          "A copy of local_ray with the segment end recomputed from ray (same o and d, new tmax)");
    m.def("check_frame", &check_frame, py::arg("frame"), py::arg("fmt"));
    m.def("local_frame_for", &local_frame_for, py::arg("box"), py::arg("fmt"), py::arg("uniform") = false,
          "The tightest frame of the format holding the box");
    m.def("local_child_frame", [](const Box& child, const LocalFrame& parent, const LocalBox& qchild,
                                  const LocalFormat& f, bool uniform) {
        f.validate();
        check_frame(parent, f);
        check_local_box(qchild, f, "qchild");
        return local_child_frame(child, parent, qchild, f, uniform);
    }, py::arg("child"), py::arg("parent"), py::arg("qchild"), py::arg("fmt"), py::arg("uniform") = false,
          "The frame of a child node from its parent's frame and its box there (qchild)");
    m.def("local_quantize_box", &local_quantize_box, py::arg("box"), py::arg("frame"), py::arg("fmt"),
          "The box in the frame, rounded outward (conservative) or to nearest");
    m.def("local_pair", [](int k) {
        if (k < 0 || k > 5) throw InputError("edge pair " + std::to_string(k) + " is outside 0..5");
        return std::pair<int, int>(local_pair_i(k), local_pair_j(k));
    }, py::arg("k"), "The axes (i, j) of edge test k = 0..5: the order of W in the node ray (local.hpp)");
    m.def("local_node_ray", [](const LocalRay& r, const LocalFrame& fr, const LocalFormat& f) {
        check_local_ray(r, f);
        check_frame(fr, f);
        return local_node_ray(r, fr, f);
    }, py::arg("ray"), py::arg("frame"), py::arg("fmt"), "The node ray of a set-up ray in a frame (per node)");
    m.def("local_hit", [](const LocalNodeRay& r, const LocalBox& b, const LocalFormat& f) {
        check_local_node_ray(r, f);
        check_local_box(b, f);
        return local_hit(r, b, f);
    }, py::arg("node_ray"), py::arg("box"), py::arg("fmt"), "The bit-exact child datapath");
    m.def("local_hit", [](const Ray& r, const Box& b, const LocalFormat& f) {
        validate_query(Query{r, b}, "local_hit");
        return local_hit(r, b, f);
    }, py::arg("ray"), py::arg("box"), py::arg("fmt"), "Set up and test one float query in its box's tightest frame");
    m.def("local_frame_out_ports", [](const LocalNodeRay& r, const LocalFormat& f) {
        return node_ray_ports(r, f, "_o");
    }, py::arg("node_ray"), py::arg("fmt"),
          "The node ray as the output port values of rtl/pluecker_local_frame.sv: a dict cls_o, dir_o, w_o, "
          "org_o, end_o (zero fields without an end), end_valid_o (x, and W_0, in the low field)");
    m.def("local_child_in_ports", &child_ports, py::arg("node_ray"), py::arg("box"), py::arg("fmt"),
          "A node ray and a box as the input port values of rtl/pluecker_local_child.sv");
    m.def("local_render_queries", &local_render_queries, py::arg("scene"), py::arg("size"), py::arg("fmt"),
          py::arg("limit") = 0, py::arg("frames") = "parent", py::arg("cells") = "axis",
          "The box queries a local-frame render (dsa order, size x size pixels) issues, in order: a list of "
          "(LocalRay, LocalFrame, LocalBox, node); at most `limit` (0: all)");

    py::class_<LocalPortContract>(m, "LocalPortContract",
                                  "The port contract of rtl/pluecker_local_intersector.sv for one configuration "
                                  "(local_contract.hpp)")
        .def(py::init(&make_local_contract), py::arg("box_bits") = LocalContractDefaults::kBoxBits,
             py::arg("dir_bits") = LocalContractDefaults::kDirBits,
             py::arg("grid_bits") = LocalContractDefaults::kGridBits,
             py::arg("tag_bits") = LocalContractDefaults::kTagBits, py::arg("conservative") = true,
             py::arg("mul_style") = "auto", py::arg("children") = LocalContractDefaults::kChildren)
        .def_property_readonly("box_bits", [](const LocalPortContract& c) { return c.config().box_bits; })
        .def_property_readonly("dir_bits", [](const LocalPortContract& c) { return c.config().dir_bits; })
        .def_property_readonly("grid_bits", [](const LocalPortContract& c) { return c.config().grid_bits; })
        .def_property_readonly("tag_bits", [](const LocalPortContract& c) { return c.config().tag_bits; })
        .def_property_readonly("conservative", [](const LocalPortContract& c) { return c.config().conservative; })
        .def_property_readonly("mul_style", [](const LocalPortContract& c) { return c.config().mul_style; })
        .def_property_readonly("children", [](const LocalPortContract& c) { return c.config().children; })
        .def_property_readonly("format", &LocalPortContract::format)
        .def_property_readonly("exp_bits", &LocalPortContract::exp_bits)
        .def_property_readonly("frame_fabric", &LocalPortContract::frame_fabric)
        .def_property_readonly("child_fabric", &LocalPortContract::child_fabric)
        .def_property_readonly("frame_mul_add", &LocalPortContract::frame_mul_add)
        .def_property_readonly("child_mul_add", &LocalPortContract::child_mul_add)
        .def_property_readonly("frame_latency", &LocalPortContract::frame_latency)
        .def_property_readonly("child_latency", &LocalPortContract::child_latency)
        .def_property_readonly("latency", &LocalPortContract::latency)
        .def_property_readonly("fifo_depth", &LocalPortContract::fifo_depth)
        .def_property_readonly("frame_dsp_blocks", &LocalPortContract::frame_dsp_blocks)
        .def_property_readonly("child_dsp_blocks", &LocalPortContract::child_dsp_blocks)
        .def_property_readonly("dsp_blocks", &LocalPortContract::dsp_blocks, "MULT18X18D of one unit")
        .def_property_readonly("ports", &LocalPortContract::ports)
        .def("port", &LocalPortContract::port, py::arg("name"), py::return_value_policy::copy)
        .def("rtl_ports", [](const LocalPortContract& c, const LocalRay& r, const LocalFrame& fr,
                             const std::vector<LocalBox>& boxes) { return local_rtl_ports(r, fr, boxes, c); },
             py::arg("ray"), py::arg("frame"), py::arg("boxes"),
             "Port values of one query (CHILDREN boxes): a dict from input port name to an unsigned int")
        .def_readonly_static("MAX_GRID_BITS", &LocalContractLimits::kMaxGridBits)
        .def_readonly_static("MAX_CHILDREN", &LocalContractLimits::kMaxChildren)
        .def("__repr__", [](const LocalPortContract& c) {
            const LocalRtlConfig& k = c.config();
            return "LocalPortContract(box_bits=" + std::to_string(k.box_bits) + ", dir_bits=" +
                   std::to_string(k.dir_bits) + ", grid_bits=" + std::to_string(k.grid_bits) + ", tag_bits=" +
                   std::to_string(k.tag_bits) + ", conservative=" + (k.conservative ? "True" : "False") +
                   ", mul_style='" + mul_style_name(k.mul_style) + "', children=" + std::to_string(k.children) +
                   "): LATENCY " + std::to_string(c.latency()) + ", FIFO_DEPTH " + std::to_string(c.fifo_depth());
        });
    m.def("local_contract_classes", [] {
        py::list out;
        for (const LocalContractClass& k : local_contract_classes()) out.append(local_class_dict(k));
        return out;
    }, "The configuration classes of the local unit's port contract (rtl/pluecker_local_contract.json)");
}
