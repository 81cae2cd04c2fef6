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
#include "pluecker/contract.hpp"
#include "pluecker/f32unit.hpp"
#include "pluecker/fixed.hpp"
#include "pluecker/float_contract.hpp"
#include "pluecker/geometry.hpp"
#include "pluecker/query.hpp"
#include "pluecker/querygen.hpp"

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

// A port value (contract.hpp's 32-bit words, least significant first) as a
// Python int: up to 72 bits, so it is assembled word by word.
py::int_ port_int(const PortWords& w) {
    py::object acc = py::int_(0);
    for (std::size_t k = w.size(); k-- > 0;) acc = (acc << py::int_(32)) | py::int_(w[k]);
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
    throw InputError("mul_style must be a MulStyle or one of 'auto', 'dsp', 'lut'");
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
    d["multiplier"] = k.fabric ? "lut" : "dsp";
    d["mul_add"] = k.mul_add;
    d["s2x_stages"] = k.s2x_stages;
    d["latency"] = k.latency;
    d["fifo_depth"] = k.fifo_depth;
    d["mult18x18d"] = k.dsp_blocks;
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
        if (c < 0 || c > 7) throw InputError("ray class " + std::to_string(c) + " is outside 0..7");
        return class_name(static_cast<RayClass>(c));
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
                 if (cls < 0 || cls > 7) throw InputError("ray class " + std::to_string(cls) + " is outside 0..7");
                 FixedRay r;
                 r.cls = static_cast<RayClass>(cls);
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
                          if (c < 0 || c > 7) throw InputError("ray class " + std::to_string(c) + " is outside 0..7");
                          r.cls = static_cast<RayClass>(c);
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
    m.def("rtl_ports", &rtl_ports, py::arg("ray"), py::arg("box"), py::arg("fmt"),
          "Port values of rtl/pluecker_intersector.sv for one quantised query: a dict from port name "
          "(ray_class_i, ray_org_i, ray_dir_i, ray_end_i, ray_end_valid_i, box_min_i, box_max_i) to an "
          "unsigned int; x in the low field, two's complement coordinates (the port contract's packing)");

    // --- the port contract (contract.hpp) ----------------------------------
    py::enum_<MulStyle>(m, "MulStyle")
        .value("Auto", MulStyle::Auto)
        .value("Dsp", MulStyle::Dsp)
        .value("Lut", MulStyle::Lut);
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
        .def_property_readonly("ports", &PortContract::ports)
        .def("port", &PortContract::port, py::arg("name"), py::return_value_policy::copy)
        .def("rtl_ports", [](const PortContract& c, const FixedRay& r, const FixedBox& b) {
            return rtl_ports(r, b, c.format());
        }, py::arg("ray"), py::arg("box"), "rtl_ports(ray, box, self.format)")
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
}
