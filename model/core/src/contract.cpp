// SPDX-License-Identifier: MIT
// The port contract of rtl/pluecker_intersector.sv (contract.hpp): the
// derived constants, the port encoding of a query and the generated files.
#include "pluecker/contract.hpp"

#include "pluecker/axis_contract.hpp"

#include "contract_util.hpp"
#include "grid.hpp"

#include "pluecker/fixed.hpp"
#include "pluecker/geometry.hpp"

#include <sstream>

namespace pluecker {
namespace {

using i64 = std::int64_t;
using L = ContractLimits;

using detail::axis_name;

constexpr MulStyle kStyles[] = {MulStyle::Auto, MulStyle::Dsp, MulStyle::Lut, MulStyle::Rom};

bool split(int operand_bits) { return operand_bits > L::kDspOperandBits; }

bool is_fabric(const RtlConfig& c) {
    return c.mul_style == MulStyle::Lut ||
           (c.mul_style == MulStyle::Auto && c.coord_bits <= L::kMulLutMaxBits && c.dir_bits <= L::kMulLutMaxBits);
}

int mul_add_of(const RtlConfig& c) { return (split(c.coord_bits + 1) ? 1 : 0) + (split(c.dir_bits + 1) ? 1 : 0); }

void check_width(int bits, const char* name) {
    if (bits < L::kMinBits || bits > L::kMaxBits)
        throw InputError(std::string(name) + " = " + std::to_string(bits) + " is outside the supported " +
                         std::to_string(L::kMinBits) + ".." + std::to_string(L::kMaxBits));
}

PortWords pack3(const std::array<i64, 3>& v, int bits) {
    PortWords w{};
    for (int a = 0; a < 3; ++a) detail::put_field(w, a * bits, bits, static_cast<std::uint64_t>(v[static_cast<std::size_t>(a)]));
    return w;
}

std::array<i64, 3> unpack3(const PortWords& w, int bits, bool is_signed) {
    std::array<i64, 3> v{};
    for (int a = 0; a < 3; ++a) v[static_cast<std::size_t>(a)] = detail::field_value(w, a * bits, bits, is_signed);
    return v;
}

void check_coord(i64 v, const FixedFormat& f, const std::string& what, int axis) {
    if (v < f.coord_min() || v > f.coord_max())
        throw InputError(what + " " + axis_name(axis) + " = " + std::to_string(v) + " does not fit COORD_BITS = " +
                         std::to_string(f.coord_bits) + " (range " + std::to_string(f.coord_min()) + ".." +
                         std::to_string(f.coord_max()) + ")");
}

// Every derived constant of one configuration (valid = the RTL takes it).
struct Row {
    bool valid = false;
    bool fabric = false;
    int mul_add = 0, s2x = 0, latency = 0, fifo_depth = 0, dsp = 0;
    bool rom = false;
    int rom_blocks = 0;
    bool operator==(const Row&) const = default;
};

Row row_of(int c, int d, MulStyle s, int p) {
    RtlConfig cfg;
    cfg.coord_bits = c;
    cfg.dir_bits = d;
    cfg.mul_style = s;
    cfg.pipeline = p;
    Row r;
    try {
        const PortContract pc(cfg);
        r = Row{true, pc.fabric_multipliers(), pc.mul_add(), pc.s2x_stages(), pc.latency(), pc.fifo_depth(),
                pc.dsp_blocks(), pc.rom_multipliers(), pc.rom_blocks()};
    } catch (const InputError&) {
        r.valid = false;
    }
    return r;
}

// Maximal runs lo..hi of widths over which every row (for every other
// width, style and PIPELINE) is the same; `coord` picks the axis.
std::vector<std::pair<int, int>> width_runs(bool coord) {
    return detail::width_runs(L::kMinBits, L::kMaxBits, [coord](int w) {
        std::vector<Row> sig;
        for (int o = L::kMinBits; o <= L::kMaxBits; ++o)
            for (MulStyle s : kStyles)
                for (int p = 0; p <= L::kMaxPipeline; ++p) sig.push_back(coord ? row_of(w, o, s, p) : row_of(o, w, s, p));
        return sig;
    });
}

const char* multiplier_name(const ContractClass& c) { return c.rom ? "rom" : c.fabric ? "lut" : "dsp"; }

}  // namespace

const char* mul_style_name(MulStyle s) {
    switch (s) {
        case MulStyle::Auto: return "auto";
        case MulStyle::Dsp: return "dsp";
        case MulStyle::Lut: return "lut";
        case MulStyle::Rom: return "rom";
    }
    return "?";
}

void validate_rtl_config(const RtlConfig& c) {
    check_width(c.coord_bits, "COORD_BITS");
    check_width(c.dir_bits, "DIR_BITS");
    if (c.tag_bits < L::kMinTagBits)
        throw InputError("TAG_BITS = " + std::to_string(c.tag_bits) + " is below the minimum " +
                         std::to_string(L::kMinTagBits));
    if (c.pipeline < 0 || c.pipeline > L::kMaxPipeline)
        throw InputError("PIPELINE = " + std::to_string(c.pipeline) + " is outside 0.." +
                         std::to_string(L::kMaxPipeline));
    if (c.mul_style != MulStyle::Auto && c.mul_style != MulStyle::Dsp && c.mul_style != MulStyle::Lut &&
        c.mul_style != MulStyle::Rom)
        throw InputError("MUL_STYLE is not one of auto, dsp, lut, rom");
    if (c.mul_style == MulStyle::Lut && mul_add_of(c) != 0)
        throw InputError("MUL_STYLE lut supports COORD_BITS and DIR_BITS up to " +
                         std::to_string(L::kDspOperandBits - 1) + " (COORD_BITS = " + std::to_string(c.coord_bits) +
                         ", DIR_BITS = " + std::to_string(c.dir_bits) + ")");
    if (c.mul_style == MulStyle::Rom) {
        if (c.pipeline != L::kMaxPipeline)
            throw InputError("MUL_STYLE rom needs PIPELINE = " + std::to_string(L::kMaxPipeline) + " (PIPELINE = " +
                             std::to_string(c.pipeline) + ")");
        if (c.coord_bits + 1 + (c.dir_bits + 1) / 2 > L::kRomAddressBits)
            throw InputError("MUL_STYLE rom needs COORD_BITS + 1 + ceil(DIR_BITS / 2) <= " +
                             std::to_string(L::kRomAddressBits) + ", one 1K x 18 block-RAM port (COORD_BITS = " +
                             std::to_string(c.coord_bits) + ", DIR_BITS = " + std::to_string(c.dir_bits) + ")");
    }
}

PortContract::PortContract(const RtlConfig& config) : config_(config) {
    validate_rtl_config(config_);
    fabric_ = is_fabric(config_);
    mul_add_ = mul_add_of(config_);
    const int c = config_.coord_bits, d = config_.dir_bits, t = config_.tag_bits;
    using D = PortDir;
    ports_ = {
        {"clk_i", D::In, 1, 1, false},
        {"rst_i", D::In, 1, 1, false},
        {"in_valid_i", D::In, 1, 1, false},
        {"in_ready_o", D::Out, 1, 1, false},
        {"in_tag_i", D::In, 1, t, false},
        {"ray_class_i", D::In, 3, 1, false},
        {"ray_org_i", D::In, 3, c, true},
        {"ray_dir_i", D::In, 3, d, false},
        {"ray_end_i", D::In, 3, c, true},
        {"ray_end_valid_i", D::In, 1, 1, false},
        {"box_min_i", D::In, 3, c, true},
        {"box_max_i", D::In, 3, c, true},
        {"out_valid_o", D::Out, 1, 1, false},
        {"out_ready_i", D::In, 1, 1, false},
        {"out_tag_o", D::Out, 1, t, false},
        {"out_hit_o", D::Out, 1, 1, false},
        {"out_strict_o", D::Out, 1, 1, false},  // TERNARY = 1 only (ternary.hpp), else 0
    };
}

FixedFormat PortContract::format() const {
    FixedFormat f;
    f.coord_bits = config_.coord_bits;
    f.dir_bits = config_.dir_bits;
    f.mode = config_.conservative ? FixedMode::Conservative : FixedMode::Nearest;
    return f;
}

int PortContract::fifo_depth() const {
    int depth = 1;
    while (depth < latency() + 2) depth <<= 1;
    return depth;
}

bool PortContract::paired_products() const {
    // a*(b0 + b1 2^K), K = WA - 1 + D, must fit the unsigned 18-bit port.
    return !fabric_ && !rom_multipliers() && config_.pipeline == 2 &&
           config_.coord_bits + 2 * config_.dir_bits <= L::kDspOperandBits;
}

int PortContract::dsp_blocks() const {
    if (fabric_ || rom_multipliers()) return 0;
    if (paired_products()) return L::kProducts / 2;
    return L::kProducts * (split(mul_a_bits()) ? 2 : 1) * (split(mul_b_bits()) ? 2 : 1);
}

int PortContract::rom_blocks() const { return rom_multipliers() ? L::kProducts : 0; }

const PortSpec& PortContract::port(std::string_view name) const {
    for (const PortSpec& p : ports_)
        if (p.name == name) return p;
    throw InputError("'" + std::string(name) + "' is not a port of pluecker_intersector");
}

void check_query_operands(const FixedRay& r, const FixedBox& b, const FixedFormat& f) {
    f.validate();
    if (r.cls > 7) throw InputError("ray class " + std::to_string(r.cls) + " is outside 0..7");
    const i64 dir_max = (i64{1} << f.dir_bits) - 1;
    for (int a = 0; a < 3; ++a) {
        const auto k = static_cast<std::size_t>(a);
        check_coord(r.org[k], f, "ray origin", a);
        check_coord(r.end[k], f, "ray end", a);
        check_coord(b.lo[k], f, "box lo", a);
        check_coord(b.hi[k], f, "box hi", a);
        if (r.dir[k] < 0 || r.dir[k] > dir_max)
            throw InputError(std::string("ray direction ") + axis_name(a) + " = " + std::to_string(r.dir[k]) +
                             " does not fit DIR_BITS = " + std::to_string(f.dir_bits) + " (range 0.." +
                             std::to_string(dir_max) + ")");
    }
}

QueryPorts pack_query(const FixedRay& r, const FixedBox& b, const FixedFormat& f) {
    check_query_operands(r, b, f);
    QueryPorts p;
    p.ray_class = r.cls;
    p.ray_org = pack3(r.org, f.coord_bits);
    p.ray_dir = pack3(r.dir, f.dir_bits);
    p.ray_end = pack3(r.end, f.coord_bits);
    p.ray_end_valid = r.has_end ? 1 : 0;
    p.box_min = pack3(b.lo, f.coord_bits);
    p.box_max = pack3(b.hi, f.coord_bits);
    return p;
}

void unpack_query(const QueryPorts& p, const FixedFormat& f, FixedRay& r, FixedBox& b) {
    f.validate();
    r = FixedRay{};
    r.cls = static_cast<RayClass>(p.ray_class & 7u);
    r.org = unpack3(p.ray_org, f.coord_bits, true);
    r.dir = unpack3(p.ray_dir, f.dir_bits, false);
    r.end = unpack3(p.ray_end, f.coord_bits, true);
    r.has_end = (p.ray_end_valid & 1u) != 0;
    b.lo = unpack3(p.box_min, f.coord_bits, true);
    b.hi = unpack3(p.box_max, f.coord_bits, true);
}

std::vector<ContractClass> contract_classes() {
    const auto coord_runs = width_runs(true);
    const auto dir_runs = width_runs(false);
    std::vector<ContractClass> out;
    for (MulStyle s : kStyles)
        for (int p = 0; p <= L::kMaxPipeline; ++p)
            for (const auto& [clo, chi] : coord_runs)
                for (const auto& [dlo, dhi] : dir_runs) {
                    const Row r = row_of(clo, dlo, s, p);
                    if (!r.valid) continue;
                    out.push_back(ContractClass{clo, chi, dlo, dhi, s, p, r.fabric, r.mul_add, r.s2x, r.latency,
                                                r.fifo_depth, r.dsp, r.rom, r.rom_blocks});
                }
    return out;
}

std::string contract_sv_package() {
    const auto classes = contract_classes();
    std::ostringstream s;
    s << "// SPDX-License-Identifier: MIT\n"
         "// Generated from model/core/src/contract.cpp by `pluecker contract --write rtl`: do\n"
         "// not edit (the test Contract.GeneratedFilesAreCurrent compares this file).\n"
         "//\n"
         "// The port contract of pluecker_intersector (model/core/include/pluecker/contract.hpp):\n"
         "// the parameter limits the module checks and the configuration classes,\n"
         "// each with the constants the module must derive from its parameters. The\n"
         "// module looks its configuration up (contract_class) and fails elaboration\n"
         "// when what it derives differs from the class's row.\n"
         "package pluecker_contract_pkg;\n"
         "  localparam int MIN_BITS = " << L::kMinBits << ";  // COORD_BITS, DIR_BITS\n"
         "  localparam int MAX_BITS = " << L::kMaxBits << ";\n"
         "  localparam int MIN_TAG_BITS = " << L::kMinTagBits << ";\n"
         "  localparam int MAX_PIPELINE = " << L::kMaxPipeline << ";\n"
         "  // A multiplier operand wider than this is split over two DSP operands.\n"
         "  localparam int DSP_OPERAND_BITS = " << L::kDspOperandBits << ";\n"
         "  // MUL_STYLE \"auto\": fabric multipliers when both widths are at most this.\n"
         "  localparam int MUL_LUT_MAX_BITS = " << L::kMulLutMaxBits << ";\n"
         "  // MUL_STYLE \"rom\": address bits of one block-RAM read port (1K x 18).\n"
         "  localparam int ROM_ADDRESS_BITS = " << L::kRomAddressBits << ";\n"
         "\n"
         "  // The class of a configuration (c = COORD_BITS, d = DIR_BITS, s = MUL_STYLE\n"
         "  // as a 32-bit pattern, p = PIPELINE), -1 when the module refuses it.\n"
         "  function automatic int contract_class(input int c, input int d, input logic [31:0] s, input int p);\n"
         "    contract_class = -1;\n";
    for (std::size_t k = 0; k < classes.size(); ++k) {
        const ContractClass& c = classes[k];
        s << "    if (c >= " << c.coord_lo << " && c <= " << c.coord_hi << " && d >= " << c.dir_lo << " && d <= "
          << c.dir_hi << " && s == 32'(\"" << mul_style_name(c.mul_style) << "\") && p == " << c.pipeline
          << ") contract_class = " << k << ";\n";
    }
    s << "  endfunction\n";
    auto table = [&](const char* name, const char* type, const char* what, auto value) {
        detail::write_sv_table(s, classes, name, type, what, value);
    };
    table("contract_mul_lut", "bit", "1: fabric multipliers (pluecker_mul_lut), 0: pluecker_mul",
          [](const ContractClass& c) { return c.fabric ? 1 : 0; });
    table("contract_mul_rom", "bit", "1: table multipliers (pluecker_mul_rom)",
          [](const ContractClass& c) { return c.rom ? 1 : 0; });
    table("contract_mul_add", "int", "MUL_ADD", [](const ContractClass& c) { return c.mul_add; });
    table("contract_latency", "int", "LATENCY", [](const ContractClass& c) { return c.latency; });
    table("contract_fifo_depth", "int", "FIFO_DEPTH", [](const ContractClass& c) { return c.fifo_depth; });
    table("contract_mult18x18d", "int", "MULT18X18D of one unit", [](const ContractClass& c) { return c.dsp_blocks; });
    table("contract_dp16kd", "int", "DP16KD of one unit's multipliers",
          [](const ContractClass& c) { return c.rom_blocks; });
    s << axis_sv_functions();
    s << "endpackage\n";
    return s.str();
}

std::string contract_json() {
    const RtlConfig def;
    std::ostringstream s;
    s << "{\n"
         "  \"generated_by\": \"pluecker contract --write rtl (model/core/src/contract.cpp); do not edit\",\n"
         "  \"limits\": {\"coord_bits\": ["
      << L::kMinBits << ", " << L::kMaxBits << "], \"dir_bits\": [" << L::kMinBits << ", " << L::kMaxBits
      << "], \"tag_bits_min\": " << L::kMinTagBits << ", \"pipeline\": [0, " << L::kMaxPipeline
      << "], \"mul_styles\": [\"auto\", \"dsp\", \"lut\", \"rom\"], \"dsp_operand_bits\": "
      << L::kDspOperandBits << ", \"mul_lut_max_bits\": " << L::kMulLutMaxBits
      << ", \"rom_address_bits\": " << L::kRomAddressBits << "},\n"
      << "  \"defaults\": {\"coord_bits\": " << def.coord_bits << ", \"dir_bits\": " << def.dir_bits
      << ", \"tag_bits\": " << def.tag_bits << ", \"conservative\": " << (def.conservative ? 1 : 0)
      << ", \"mul_style\": \"" << mul_style_name(def.mul_style) << "\", \"pipeline\": " << def.pipeline << "},\n"
      << "  \"classes\": [\n";
    const auto classes = contract_classes();
    for (std::size_t k = 0; k < classes.size(); ++k) {
        const ContractClass& c = classes[k];
        s << "    {\"coord_bits\": [" << c.coord_lo << ", " << c.coord_hi << "], \"dir_bits\": [" << c.dir_lo << ", "
          << c.dir_hi << "], \"mul_style\": \"" << mul_style_name(c.mul_style) << "\", \"pipeline\": " << c.pipeline
          << ", \"multiplier\": \"" << multiplier_name(c) << "\", \"mul_add\": " << c.mul_add
          << ", \"s2x_stages\": " << c.s2x_stages << ", \"latency\": " << c.latency
          << ", \"fifo_depth\": " << c.fifo_depth << ", \"mult18x18d\": " << c.dsp_blocks
          << ", \"dp16kd\": " << c.rom_blocks << "}"
          << (k + 1 < classes.size() ? "," : "") << "\n";
    }
    s << "  ]\n}\n";
    return s.str();
}

}  // namespace pluecker
