// SPDX-License-Identifier: MIT
// pybind11 module `pluecker_py`: the golden model as the cocotb benches and
// scripts see it. Every answer comes from the C++ library; Python only moves
// values around (rtl_ports packs the fixed-point operands into the port
// integers of rtl/pluecker_intersector.sv without any arithmetic on them).
//
// Vectors are passed as any sequence of three numbers and returned as
// tuples. Bad arguments raise pluecker_py.InputError, a ValueError.
#include "pluecker/app/names.hpp"  // parse_fixed_mode
#include "pluecker/boxtest.hpp"
#include "pluecker/fixed.hpp"
#include "pluecker/geometry.hpp"
#include "pluecker/query.hpp"
#include "pluecker/querygen.hpp"

#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <array>
#include <cstdint>
#include <sstream>
#include <string>
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

const char* axis_name(int a) { return a == 0 ? "x" : a == 1 ? "y" : "z"; }

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

// Every operand must fit its port: coordinates COORD_BITS two's complement,
// directions DIR_BITS unsigned (the RTL computes any such value exactly,
// the set-up produces at most 2^(DIR_BITS-1)).
void check_coord(i64 v, const FixedFormat& f, const std::string& what, int axis) {
    if (v < f.coord_min() || v > f.coord_max())
        throw InputError(what + " " + axis_name(axis) + " = " + std::to_string(v) + " does not fit COORD_BITS = " +
                         std::to_string(f.coord_bits) + " (range " + std::to_string(f.coord_min()) + ".." +
                         std::to_string(f.coord_max()) + ")");
}

void check_operands(const FixedRay& r, const FixedBox& b, const FixedFormat& f) {
    f.validate();
    if (r.cls > 7) throw InputError("ray class " + std::to_string(r.cls) + " is outside 0..7");
    const i64 dir_max = (i64{1} << f.dir_bits) - 1;
    for (int a = 0; a < 3; ++a) {
        check_coord(r.org[a], f, "ray origin", a);
        check_coord(r.end[a], f, "ray end", a);
        check_coord(b.lo[a], f, "box lo", a);
        check_coord(b.hi[a], f, "box hi", a);
        if (r.dir[a] < 0 || r.dir[a] > dir_max)
            throw InputError(std::string("ray direction ") + axis_name(a) + " = " + std::to_string(r.dir[a]) +
                             " does not fit DIR_BITS = " + std::to_string(f.dir_bits) + " (range 0.." +
                             std::to_string(dir_max) + ")");
    }
}

// Three fields of `bits` bits each, x in the low field, as a Python int
// (up to 72 bits, so it is assembled field by field in Python integers).
py::int_ pack3(const std::array<i64, 3>& v, int bits) {
    const std::uint64_t mask = (std::uint64_t{1} << bits) - 1;
    py::object acc = py::int_(0);
    for (int a = 2; a >= 0; --a) {
        const py::int_ field(static_cast<std::uint64_t>(v[a]) & mask);
        acc = (acc << py::int_(bits)) | field;
    }
    return py::int_(acc);
}

py::dict rtl_ports(const FixedRay& r, const FixedBox& b, const FixedFormat& f) {
    check_operands(r, b, f);
    py::dict d;
    d["ray_class_i"] = py::int_(static_cast<unsigned>(r.cls));
    d["ray_org_i"] = pack3(r.org, f.coord_bits);
    d["ray_dir_i"] = pack3(r.dir, f.dir_bits);
    d["ray_end_i"] = pack3(r.end, f.coord_bits);
    d["ray_end_valid_i"] = py::int_(r.has_end ? 1 : 0);
    d["box_min_i"] = pack3(b.lo, f.coord_bits);
    d["box_max_i"] = pack3(b.hi, f.coord_bits);
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
        check_operands(r, b, f);
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
          "unsigned int; x in the low field, two's complement coordinates");
}
