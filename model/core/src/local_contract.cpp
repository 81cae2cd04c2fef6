// SPDX-License-Identifier: MIT
// The port contract of rtl/pluecker_local_intersector.sv (local_contract.hpp):
// the derived constants, the port encoding of a query and the generated files.
#include "pluecker/local_contract.hpp"

#include "contract_util.hpp"
#include "pluecker/geometry.hpp"

#include <algorithm>
#include <sstream>

namespace pluecker {
namespace {

using i64 = std::int64_t;
using L = LocalContractLimits;

const char* axis_name(int a) { return a == 0 ? "x" : a == 1 ? "y" : "z"; }

constexpr MulStyle kStyles[] = {MulStyle::Auto, MulStyle::Dsp, MulStyle::Lut};

int split(int operand_bits) { return operand_bits > L::kDspOperandBits ? 1 : 0; }

void check_range(int v, int lo, int hi, const std::string& name, const std::string& rule = "") {
    if (v < lo || v > hi)
        throw InputError(name + " = " + std::to_string(v) + " is outside the supported " + std::to_string(lo) + ".." +
                         std::to_string(hi) + rule);
}

// Every derived constant of one configuration; the rows of the class table
// (valid = the RTL takes the widths and style).
struct Row {
    bool valid = false;
    bool frame_fabric = false, child_fabric = false;
    int frame_mul_add = 0, child_mul_add = 0, latency = 0, fifo_depth = 0, frame_dsp = 0, child_dsp = 0;
    bool operator==(const Row&) const = default;
};

Row row_of(int d, int g, MulStyle s) {
    LocalRtlConfig cfg;
    cfg.box_bits = L::kMinBoxBits;  // the rows do not depend on BOX_BITS
    cfg.dir_bits = d;
    cfg.grid_bits = g;
    cfg.mul_style = s;
    Row r;
    try {
        const LocalPortContract pc(cfg);
        r = Row{true,           pc.frame_fabric(), pc.child_fabric(),     pc.frame_mul_add(),    pc.child_mul_add(),
                pc.latency(),   pc.fifo_depth(),   pc.frame_dsp_blocks(), pc.child_dsp_blocks()};
    } catch (const InputError&) {
        r.valid = false;
    }
    return r;
}

std::vector<std::pair<int, int>> dir_runs() {
    return detail::width_runs(L::kMinDirBits, L::kMaxDirBits, [](int d) {
        std::vector<Row> sig;
        for (int g = L::kMinGridBits; g <= L::kMaxGridBits; ++g)
            for (MulStyle s : kStyles) sig.push_back(row_of(d, g, s));
        return sig;
    });
}

std::vector<std::pair<int, int>> grid_runs() {
    return detail::width_runs(L::kMinGridBits, L::kMaxGridBits, [](int g) {
        std::vector<Row> sig;
        for (int d = L::kMinDirBits; d <= L::kMaxDirBits; ++d)
            for (MulStyle s : kStyles) sig.push_back(row_of(d, g, s));
        return sig;
    });
}

const char* multiplier_name(bool fabric) { return fabric ? "lut" : "dsp"; }

void check_grid_value(i64 v, const LocalFormat& f, const std::string& what, int axis) {
    if (v < f.grid_min() || v > f.grid_max())
        throw InputError(what + " " + axis_name(axis) + " = " + std::to_string(v) + " does not fit GRID_BITS = " +
                         std::to_string(f.grid_bits) + " (range " + std::to_string(f.grid_min()) + ".." +
                         std::to_string(f.grid_max()) + ")");
}

}  // namespace

int local_exp_bits(int grid_bits, int box_bits) {
    int bits = 0;
    while ((1 << bits) < grid_bits - box_bits + 2) ++bits;
    return bits;
}

void validate_local_rtl_config(const LocalRtlConfig& c) {
    check_range(c.box_bits, L::kMinBoxBits, L::kMaxBoxBits, "BOX_BITS");
    check_range(c.dir_bits, L::kMinDirBits, L::kMaxDirBits, "DIR_BITS");
    check_range(c.grid_bits, c.box_bits + L::kGridMargin, L::kMaxGridBits, "GRID_BITS",
                " (BOX_BITS + " + std::to_string(L::kGridMargin) + ".." + std::to_string(L::kMaxGridBits) + ")");
    if (c.tag_bits < L::kMinTagBits)
        throw InputError("TAG_BITS = " + std::to_string(c.tag_bits) + " is below the minimum " +
                         std::to_string(L::kMinTagBits));
    check_range(c.children, 1, L::kMaxChildren, "CHILDREN");
    if (c.mul_style != MulStyle::Auto && c.mul_style != MulStyle::Dsp && c.mul_style != MulStyle::Lut)
        throw InputError("MUL_STYLE is not one of auto, dsp, lut");
}

LocalPortContract::LocalPortContract(const LocalRtlConfig& config) : config_(config) {
    validate_local_rtl_config(config_);
    const int g = config_.grid_bits, k = config_.box_bits, t = config_.tag_bits, ch = config_.children;
    using D = PortDir;
    ports_ = {
        {"clk_i", D::In, 1, 1, false},
        {"rst_i", D::In, 1, 1, false},
        {"in_valid_i", D::In, 1, 1, false},
        {"in_ready_o", D::Out, 1, 1, false},
        {"in_tag_i", D::In, 1, t, false},
        {"ray_class_i", D::In, 3, 1, false},
        {"ray_org_i", D::In, 3, g, true},
        {"ray_dir_i", D::In, 3, g, false},
        {"ray_end_i", D::In, 3, g, true},
        {"ray_end_valid_i", D::In, 1, 1, false},
        {"frame_org_i", D::In, 3, g, true},
        {"frame_exp_i", D::In, 3, exp_bits(), false},
        {"box_min_i", D::In, 3 * ch, k, false},
        {"box_max_i", D::In, 3 * ch, k, false},
        {"out_valid_o", D::Out, 1, 1, false},
        {"out_ready_i", D::In, 1, 1, false},
        {"out_tag_o", D::Out, 1, t, false},
        {"out_hit_o", D::Out, ch, 1, false},
    };
}

LocalFormat LocalPortContract::format() const {
    LocalFormat f;
    f.box_bits = config_.box_bits;
    f.dir_bits = config_.dir_bits;
    f.grid_bits = config_.grid_bits;
    f.mode = config_.conservative ? FixedMode::Conservative : FixedMode::Nearest;
    return f;
}

bool LocalPortContract::frame_fabric() const { return config_.mul_style == MulStyle::Lut; }
bool LocalPortContract::child_fabric() const { return config_.mul_style != MulStyle::Dsp; }

int LocalPortContract::frame_mul_add() const {
    return frame_fabric() ? 0 : split(config_.grid_bits + 3) + split(config_.grid_bits + 1);
}

int LocalPortContract::child_mul_add() const {
    return child_fabric() ? 0 : split(config_.dir_bits + 1) + split(config_.box_bits + 1);
}

int LocalPortContract::fifo_depth() const {
    int depth = 1;
    while (depth < latency() + 2) depth <<= 1;
    return depth;
}

int LocalPortContract::frame_dsp_blocks() const {
    if (frame_fabric()) return 0;
    return L::kMomentProducts * (1 + split(config_.grid_bits + 3)) * (1 + split(config_.grid_bits + 1));
}

int LocalPortContract::child_dsp_blocks() const {
    if (child_fabric()) return 0;
    return L::kChildProducts * (1 + split(config_.dir_bits + 1)) * (1 + split(config_.box_bits + 1));
}

const PortSpec& LocalPortContract::port(std::string_view name) const {
    for (const PortSpec& p : ports_)
        if (p.name == name) return p;
    throw InputError("'" + std::string(name) + "' is not a port of pluecker_local_intersector");
}

void check_local_ray(const LocalRay& r, const LocalFormat& f) {
    f.validate();
    if (r.cls > 7) throw InputError("ray class " + std::to_string(r.cls) + " is outside 0..7");
    const i64 top = i64{1} << (f.grid_bits - 1);
    i64 largest = 0;
    for (int a = 0; a < 3; ++a) {
        const auto k = static_cast<std::size_t>(a);
        check_grid_value(r.org[k], f, "ray origin", a);
        check_grid_value(r.end[k], f, "ray end", a);
        if (r.dir_g[k] < 0 || r.dir_g[k] > top)
            throw InputError(std::string("ray direction ") + axis_name(a) + " = " + std::to_string(r.dir_g[k]) +
                             " is outside 0.." + std::to_string(top) + " (2^(GRID_BITS - 1))");
        largest = std::max(largest, r.dir_g[k]);
    }
    if (largest != top)
        throw InputError("ray direction: the largest component is " + std::to_string(largest) +
                         ", not 2^(GRID_BITS - 1) = " + std::to_string(top) + " (the set-up scales it so)");
}

void check_local_box(const LocalBox& b, const LocalFormat& f, const std::string& what) {
    for (int a = 0; a < 3; ++a) {
        const auto k = static_cast<std::size_t>(a);
        for (const i64 v : {b.lo[k], b.hi[k]})
            if (v < 0 || v > f.box_max())
                throw InputError(what + " " + axis_name(a) + " offset " + std::to_string(v) + " is outside 0.." +
                                 std::to_string(f.box_max()) + " (BOX_BITS = " + std::to_string(f.box_bits) + ")");
    }
}

void check_local_query_operands(const LocalRay& r, const LocalFrame& fr, std::span<const LocalBox> boxes,
                                const LocalPortContract& c) {
    const LocalFormat f = c.format();
    check_local_ray(r, f);
    check_frame(fr, f);
    if (boxes.size() != static_cast<std::size_t>(c.config().children))
        throw InputError(std::to_string(boxes.size()) + " boxes for CHILDREN = " + std::to_string(c.config().children));
    for (std::size_t b = 0; b < boxes.size(); ++b) check_local_box(boxes[b], f, "box " + std::to_string(b));
}

void check_local_node_ray(const LocalNodeRay& r, const LocalFormat& f) {
    f.validate();
    if (r.cls > 7) throw InputError("node ray class " + std::to_string(r.cls) + " is outside 0..7");
    auto fits = [](i64 v, int bits, bool is_signed, const std::string& what) {
        const i64 lo = is_signed ? -(i64{1} << (bits - 1)) : 0;
        const i64 hi = is_signed ? (i64{1} << (bits - 1)) - 1 : (i64{1} << bits) - 1;
        if (v < lo || v > hi)
            throw InputError(what + " = " + std::to_string(v) + " does not fit " + std::to_string(bits) + " bits" +
                             (is_signed ? " signed" : "") + " (range " + std::to_string(lo) + ".." + std::to_string(hi) +
                             ")");
    };
    const int k = f.box_bits, d = f.dir_bits;
    for (int a = 0; a < 3; ++a) {
        const auto x = static_cast<std::size_t>(a);
        fits(r.dir[x], d, false, std::string("node ray DIR ") + axis_name(a));
        fits(r.org[x], k + 2, true, std::string("node ray ORG ") + axis_name(a));
        fits(r.end[x], k + 2, true, std::string("node ray END ") + axis_name(a));
    }
    for (std::size_t p = 0; p < r.w.size(); ++p) fits(r.w[p], k + d + 2, true, "node ray W" + std::to_string(p));
}

LocalNodeRayPorts pack_local_node_ray(const LocalNodeRay& r, const LocalFormat& f) {
    check_local_node_ray(r, f);
    const int k = f.box_bits, d = f.dir_bits, ww = k + d + 2;
    LocalNodeRayPorts p;
    p.cls = r.cls;
    for (int a = 0; a < 3; ++a) {
        const auto x = static_cast<std::size_t>(a);
        detail::put_field(p.dir, a * d, d, static_cast<std::uint64_t>(r.dir[x]));
        detail::put_field(p.org, a * (k + 2), k + 2, static_cast<std::uint64_t>(r.org[x]));
        detail::put_field(p.end, a * (k + 2), k + 2, static_cast<std::uint64_t>(r.end[x]));
    }
    for (std::size_t q = 0; q < r.w.size(); ++q) {
        // A field of up to 42 bits: two pieces of at most 32.
        const auto v = static_cast<std::uint64_t>(r.w[q]);
        const int lsb = static_cast<int>(q) * ww, lo_bits = std::min(ww, 32);
        detail::put_field(p.w, lsb, lo_bits, v);
        if (ww > 32) detail::put_field(p.w, lsb + 32, ww - 32, v >> 32);
    }
    p.end_valid = r.has_end ? 1 : 0;
    return p;
}

LocalQueryPorts pack_local_query(const LocalRay& r, const LocalFrame& fr, std::span<const LocalBox> boxes,
                                 const LocalPortContract& c) {
    check_local_query_operands(r, fr, boxes, c);
    const int g = c.config().grid_bits, e = c.exp_bits();
    LocalQueryPorts p;
    p.ray_class = r.cls;
    for (int a = 0; a < 3; ++a) {
        const auto x = static_cast<std::size_t>(a);
        detail::put_field(p.ray_org, a * g, g, static_cast<std::uint64_t>(r.org[x]));
        detail::put_field(p.ray_dir, a * g, g, static_cast<std::uint64_t>(r.dir_g[x]));
        detail::put_field(p.ray_end, a * g, g, static_cast<std::uint64_t>(r.end[x]));
        detail::put_field(p.frame_org, a * g, g, static_cast<std::uint64_t>(fr.origin[x]));
        p.frame_exp |= static_cast<std::uint32_t>(fr.exp[x]) << (a * e);
    }
    const LocalBoxPorts b = pack_local_boxes(boxes, c.format());
    p.box_min = b.box_min;
    p.box_max = b.box_max;
    p.ray_end_valid = r.has_end ? 1 : 0;
    return p;
}

LocalBoxPorts pack_local_boxes(std::span<const LocalBox> boxes, const LocalFormat& f) {
    const int k = f.box_bits;
    if (boxes.size() * 3 * static_cast<std::size_t>(k) > 96)
        throw InputError(std::to_string(boxes.size()) + " boxes of BOX_BITS = " + std::to_string(k) +
                         " do not fit a 96-bit port");
    LocalBoxPorts p;
    for (std::size_t b = 0; b < boxes.size(); ++b) {
        check_local_box(boxes[b], f, "box " + std::to_string(b));
        for (int a = 0; a < 3; ++a) {
            const auto x = static_cast<std::size_t>(a);
            const int lsb = (static_cast<int>(b) * 3 + a) * k;
            detail::put_field(p.box_min, lsb, k, static_cast<std::uint64_t>(boxes[b].lo[x]));
            detail::put_field(p.box_max, lsb, k, static_cast<std::uint64_t>(boxes[b].hi[x]));
        }
    }
    return p;
}

void unpack_local_query(const LocalQueryPorts& p, const LocalPortContract& c, LocalRay& r, LocalFrame& fr,
                        std::vector<LocalBox>& boxes) {
    const int g = c.config().grid_bits, k = c.config().box_bits, e = c.exp_bits();
    r = LocalRay{};
    fr = LocalFrame{};
    boxes.assign(static_cast<std::size_t>(c.config().children), LocalBox{});
    r.cls = static_cast<RayClass>(p.ray_class & 7u);
    for (int a = 0; a < 3; ++a) {
        const auto x = static_cast<std::size_t>(a);
        r.org[x] = detail::field_value(p.ray_org, a * g, g, true);
        r.dir_g[x] = detail::field_value(p.ray_dir, a * g, g, false);
        r.end[x] = detail::field_value(p.ray_end, a * g, g, true);
        fr.origin[x] = detail::field_value(p.frame_org, a * g, g, true);
        fr.exp[x] = static_cast<int>((p.frame_exp >> (a * e)) & ((1u << e) - 1));
        for (std::size_t b = 0; b < boxes.size(); ++b) {
            const int lsb = (static_cast<int>(b) * 3 + a) * k;
            boxes[b].lo[x] = detail::field_value(p.box_min, lsb, k, false);
            boxes[b].hi[x] = detail::field_value(p.box_max, lsb, k, false);
        }
    }
    r.has_end = (p.ray_end_valid & 1u) != 0;
}

std::vector<LocalContractClass> local_contract_classes() {
    std::vector<LocalContractClass> out;
    const auto druns = dir_runs();
    const auto gruns = grid_runs();
    for (MulStyle s : kStyles)
        for (const auto& [dlo, dhi] : druns)
            for (const auto& [glo, ghi] : gruns) {
                const Row r = row_of(dlo, glo, s);
                if (!r.valid) continue;
                out.push_back(LocalContractClass{dlo, dhi, glo, ghi, s, r.frame_fabric, r.child_fabric,
                                                 r.frame_mul_add, r.child_mul_add, r.latency, r.fifo_depth,
                                                 r.frame_dsp, r.child_dsp});
            }
    return out;
}

std::string local_contract_sv_package() {
    const auto classes = local_contract_classes();
    std::ostringstream s;
    s << "// SPDX-License-Identifier: MIT\n"
         "// Generated from model/core/src/local_contract.cpp by `pluecker contract --write rtl`:\n"
         "// do not edit (the test LocalContract.GeneratedFilesAreCurrent compares this file).\n"
         "//\n"
         "// The port contract of pluecker_local_intersector\n"
         "// (model/core/include/pluecker/local_contract.hpp): the parameter limits the\n"
         "// module checks and the configuration classes, each with the constants the\n"
         "// module must derive from its parameters. The module looks its configuration\n"
         "// up (local_contract_class) and fails elaboration when what it derives\n"
         "// differs from the class's row.\n"
         "package pluecker_local_contract_pkg;\n"
         "  localparam int MIN_BOX_BITS = " << L::kMinBoxBits << ";\n"
         "  localparam int MAX_BOX_BITS = " << L::kMaxBoxBits << ";\n"
         "  localparam int MIN_DIR_BITS = " << L::kMinDirBits << ";\n"
         "  localparam int MAX_DIR_BITS = " << L::kMaxDirBits << ";\n"
         "  // GRID_BITS is BOX_BITS + GRID_MARGIN .. MAX_GRID_BITS.\n"
         "  localparam int GRID_MARGIN = " << L::kGridMargin << ";\n"
         "  localparam int MAX_GRID_BITS = " << L::kMaxGridBits << ";\n"
         "  localparam int MIN_TAG_BITS = " << L::kMinTagBits << ";\n"
         "  localparam int MAX_CHILDREN = " << L::kMaxChildren << ";\n"
         "  // A multiplier operand wider than this is split over two DSP operands.\n"
         "  localparam int DSP_OPERAND_BITS = " << L::kDspOperandBits << ";\n"
         "\n"
         "  // The class of a configuration (d = DIR_BITS, g = GRID_BITS, s = MUL_STYLE\n"
         "  // as a 32-bit pattern), -1 when the module refuses it.\n"
         "  function automatic int local_contract_class(input int d, input int g, input logic [31:0] s);\n"
         "    local_contract_class = -1;\n";
    for (std::size_t k = 0; k < classes.size(); ++k) {
        const LocalContractClass& c = classes[k];
        s << "    if (d >= " << c.dir_lo << " && d <= " << c.dir_hi << " && g >= " << c.grid_lo << " && g <= "
          << c.grid_hi << " && s == 32'(\"" << mul_style_name(c.mul_style) << "\")) local_contract_class = " << k
          << ";\n";
    }
    s << "  endfunction\n";
    auto table = [&](const char* name, const char* type, const char* what, auto value) {
        detail::write_sv_table(s, classes, name, type, what, value);
    };
    table("local_contract_frame_lut", "bit", "1: the node set-up's products in fabric (pluecker_mul_lut)",
          [](const LocalContractClass& c) { return c.frame_fabric ? 1 : 0; });
    table("local_contract_child_lut", "bit", "1: the children's products in fabric (pluecker_mul_lut)",
          [](const LocalContractClass& c) { return c.child_fabric ? 1 : 0; });
    table("local_contract_frame_mul_add", "int", "FRAME_MUL_ADD", [](const LocalContractClass& c) { return c.frame_mul_add; });
    table("local_contract_child_mul_add", "int", "CHILD_MUL_ADD", [](const LocalContractClass& c) { return c.child_mul_add; });
    table("local_contract_latency", "int", "LATENCY", [](const LocalContractClass& c) { return c.latency; });
    table("local_contract_fifo_depth", "int", "FIFO_DEPTH", [](const LocalContractClass& c) { return c.fifo_depth; });
    s << "endpackage\n";
    return s.str();
}

std::string local_contract_json() {
    const LocalRtlConfig def;
    std::ostringstream s;
    s << "{\n"
         "  \"generated_by\": \"pluecker contract --write rtl (model/core/src/local_contract.cpp); do not edit\",\n"
         "  \"limits\": {\"box_bits\": ["
      << L::kMinBoxBits << ", " << L::kMaxBoxBits << "], \"dir_bits\": [" << L::kMinDirBits << ", " << L::kMaxDirBits
      << "], \"grid_margin\": " << L::kGridMargin << ", \"max_grid_bits\": " << L::kMaxGridBits
      << ", \"tag_bits_min\": " << L::kMinTagBits << ", \"children\": [1, " << L::kMaxChildren
      << "], \"mul_styles\": [\"auto\", \"dsp\", \"lut\"], \"dsp_operand_bits\": " << L::kDspOperandBits << "},\n"
      << "  \"defaults\": {\"box_bits\": " << def.box_bits << ", \"dir_bits\": " << def.dir_bits
      << ", \"grid_bits\": " << def.grid_bits << ", \"tag_bits\": " << def.tag_bits
      << ", \"conservative\": " << (def.conservative ? 1 : 0) << ", \"mul_style\": \"" << mul_style_name(def.mul_style)
      << "\", \"children\": " << def.children << "},\n"
      << "  \"classes\": [\n";
    const auto classes = local_contract_classes();
    for (std::size_t k = 0; k < classes.size(); ++k) {
        const LocalContractClass& c = classes[k];
        s << "    {\"dir_bits\": [" << c.dir_lo << ", " << c.dir_hi << "], \"grid_bits\": [" << c.grid_lo << ", "
          << c.grid_hi << "], \"mul_style\": \"" << mul_style_name(c.mul_style) << "\", \"frame_multiplier\": \""
          << multiplier_name(c.frame_fabric) << "\", \"child_multiplier\": \"" << multiplier_name(c.child_fabric)
          << "\", \"frame_mul_add\": " << c.frame_mul_add << ", \"child_mul_add\": " << c.child_mul_add
          << ", \"latency\": " << c.latency << ", \"fifo_depth\": " << c.fifo_depth
          << ", \"frame_mult18x18d\": " << c.frame_dsp_blocks << ", \"child_mult18x18d\": " << c.child_dsp_blocks
          << "}" << (k + 1 < classes.size() ? "," : "") << "\n";
    }
    s << "  ]\n}\n";
    return s.str();
}

}  // namespace pluecker
