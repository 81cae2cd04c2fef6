// SPDX-License-Identifier: MIT
// `pluecker contract`: the port contract of rtl/pluecker_intersector.sv (or,
// with --local, of rtl/pluecker_local_intersector.sv; with --unit, of a
// binary32 unit) for one configuration, and the generated files that carry
// them to the RTL and the scripts (model/core/include/pluecker/contract.hpp,
// local_contract.hpp, float_contract.hpp).
#include "commands.hpp"
#include "pluecker/app/names.hpp"

#include "pluecker/axis_contract.hpp"
#include "pluecker/contract.hpp"
#include "pluecker/fixed.hpp"
#include "pluecker/float_contract.hpp"
#include "pluecker/local_contract.hpp"

#include <cstdio>
#include <fstream>
#include <sstream>
#include <string>

namespace pluecker::cli {

namespace {

constexpr const char* kUsage =
    "usage: pluecker contract [--coord-bits N] [--dir-bits M] [--tag-bits T] [--mode MODE]\n"
    "                         [--mul-style STYLE] [--pipeline P]\n"
    "       pluecker contract --local [--box-bits K] [--dir-bits D] [--grid-bits G]\n"
    "                         [--children C] [--tag-bits T] [--mode MODE] [--mul-style STYLE]\n"
    "       pluecker contract --unit float|smits [--tag-bits T] [--mode MODE] [--mul-dsp M]\n"
    "       pluecker contract --write DIR | --check DIR\n"
    "Prints the port contract of rtl/pluecker_intersector.sv (with --local: of\n"
    "rtl/pluecker_local_intersector.sv) for one configuration: the constants the RTL\n"
    "derives from its parameters (multipliers, adder stages, LATENCY, FIFO_DEPTH,\n"
    "MULT18X18D) and its ports with their fields (x in the low field). With --unit,\n"
    "the contract of a binary32 unit instead (float_contract.hpp): 'float' is\n"
    "rtl/pluecker_float_intersector.sv (--mode conservative: CONSERVATIVE = 1,\n"
    "default nearest), 'smits' rtl/pluecker_smits_intersector.sv; --mul-dsp is MUL_DSP.\n"
    "--write DIR writes the generated files DIR/pluecker_contract_pkg.sv,\n"
    "DIR/pluecker_local_contract_pkg.sv and DIR/pluecker_contract_float_pkg.sv (read by\n"
    "the RTL), DIR/pluecker_contract.json, DIR/pluecker_local_contract.json and\n"
    "DIR/pluecker_contract_float.json (read by scripts/contract.py); --check DIR\n"
    "exits 1 when they differ from what --write would write. Regenerate the\n"
    "committed copies with 'pluecker contract --write rtl' (make contract).\n"
    "options:\n"
    "  --coord-bits N    COORD_BITS, 6..24                                [16]\n"
    "  --dir-bits M      DIR_BITS, 6..24                                  [16]\n"
    "  --tag-bits T      TAG_BITS, 1..64                                  [16]\n"
    "  --mode MODE       conservative (CONSERVATIVE = 1) or nearest (0)   [conservative]\n"
    "  --mul-style S     MUL_STYLE: auto, dsp or lut                      [auto]\n"
    "  --pipeline P      PIPELINE, 0..1                                   [0]\n"
    "  --unit U          float or smits: a binary32 unit's contract\n"
    "  --mul-dsp M       MUL_DSP of a binary32 unit: 1, 3 or 4            [4]\n"
    "with --local:\n"
    "  --box-bits K      BOX_BITS, 4..16                                  [8]\n"
    "  --dir-bits D      DIR_BITS, 4..24                                  [11]\n"
    "  --grid-bits G     GRID_BITS, K+2..32                               [32]\n"
    "  --children C      CHILDREN, 1..2                                   [1]\n";

std::string read_file(const std::string& path, bool& found) {
    std::ifstream in(path, std::ios::binary);
    found = static_cast<bool>(in);
    std::ostringstream s;
    s << in.rdbuf();
    return s.str();
}

struct Generated {
    const char* name;
    std::string text;
};

int write_or_check(const std::string& dir, bool write) {
    const Generated files[] = {{kContractSvFile, contract_sv_package()},
                               {kContractJsonFile, contract_json()},
                               {kFloatContractSvFile, float_contract_sv_package()},
                               {kFloatContractJsonFile, float_contract_json()},
                               {kLocalContractSvFile, local_contract_sv_package()},
                               {kLocalContractJsonFile, local_contract_json()}};
    int stale = 0;
    for (const Generated& g : files) {
        const std::string path = dir + "/" + g.name;
        if (write) {
            std::ofstream out(path, std::ios::binary);
            out << g.text;
            out.flush();
            if (!out) throw InputError("option --write: cannot write '" + path + "'");
            std::printf("contract: wrote %s\n", path.c_str());
            continue;
        }
        bool found = false;
        const std::string have = read_file(path, found);
        if (!found) {
            std::printf("contract: %s is missing\n", path.c_str());
            ++stale;
        } else if (have != g.text) {
            std::printf("contract: %s differs from the port contract of this build\n", path.c_str());
            ++stale;
        } else {
            std::printf("contract: %s is current\n", path.c_str());
        }
    }
    if (stale) std::printf("contract: regenerate with 'pluecker contract --write %s'\n", dir.c_str());
    return stale ? 1 : 0;
}

void print_ports(const std::vector<PortSpec>& ports) {
    std::printf("  ports\n");
    for (const PortSpec& p : ports) {
        std::printf("    %-16s %-3s %3d", p.name.c_str(), p.dir == PortDir::In ? "in" : "out", p.width());
        if (p.fields > 1) {
            std::printf(" = %d x %d%s:", p.fields, p.field_bits, p.is_signed ? " signed" : "");
            for (int a = 0; a < p.fields; ++a) {
                const int lo = p.field_lsb(a), hi = lo + p.field_bits - 1;
                const std::string name = p.fields == 3 ? std::string(1, "xyz"[a])
                                                       : p.fields % 3 == 0 ? std::to_string(a / 3) + "xyz"[a % 3]
                                                                           : std::to_string(a);
                if (hi == lo)
                    std::printf(" %s [%d]", name.c_str(), lo);
                else
                    std::printf(" %s [%d:%d]", name.c_str(), hi, lo);
            }
        }
        std::printf("\n");
    }
}

void print_contract(const PortContract& pc) {
    const RtlConfig& c = pc.config();
    std::printf("COORD_BITS %d, DIR_BITS %d, TAG_BITS %d, CONSERVATIVE %d, MUL_STYLE %s, PIPELINE %d\n",
                c.coord_bits, c.dir_bits, c.tag_bits, c.conservative ? 1 : 0, mul_style_name(c.mul_style),
                c.pipeline);
    std::printf("  multipliers   %s, operands %d x %d bits, %d MULT18X18D, %d DP16KD\n",
                pc.rom_multipliers()      ? "block-RAM tables (pluecker_mul_rom)"
                : pc.fabric_multipliers() ? "fabric (pluecker_mul_lut)"
                                          : "DSP (pluecker_mul)",
                pc.mul_a_bits(), pc.mul_b_bits(), pc.dsp_blocks(), pc.rom_blocks());
    std::printf("  MUL_ADD       %d\n", pc.mul_add());
    std::printf("  S2x stages    %d (PIPELINE + MUL_ADD)\n", pc.s2x_stages());
    std::printf("  LATENCY       %d\n", pc.latency());
    std::printf("  FIFO_DEPTH    %d\n", pc.fifo_depth());
    print_ports(pc.ports());
    std::printf("  AXI4-Stream wrapper (pluecker_axis): s_axis_tdata_i %d bits (%d of fields)\n", axis_tdata_bits(pc),
                axis_query_bits(pc));
    for (const TdataField& f : axis_tdata_fields(pc))
        std::printf("    tdata[%d:%d] %s\n", f.lsb + f.width - 1, f.lsb, f.port.c_str());
}

const char* multipliers_name(bool fabric) { return fabric ? "fabric (pluecker_mul_lut)" : "DSP (pluecker_mul)"; }

void print_local_contract(const LocalPortContract& pc) {
    const LocalRtlConfig& c = pc.config();
    std::printf("BOX_BITS %d, DIR_BITS %d, GRID_BITS %d, TAG_BITS %d, CONSERVATIVE %d, MUL_STYLE %s, CHILDREN %d\n",
                c.box_bits, c.dir_bits, c.grid_bits, c.tag_bits, c.conservative ? 1 : 0, mul_style_name(c.mul_style),
                c.children);
    std::printf("  EXP_BITS        %d (frame exponents 0..%d)\n", pc.exp_bits(), c.grid_bits - c.box_bits + 1);
    std::printf("  node set-up     %s, 6 products %d x %d bits, FRAME_MUL_ADD %d, %d MULT18X18D, FRAME_LATENCY %d\n",
                multipliers_name(pc.frame_fabric()), c.grid_bits + 3, c.grid_bits + 1, pc.frame_mul_add(),
                pc.frame_dsp_blocks(), pc.frame_latency());
    std::printf("  each child      %s, 12 products %d x %d bits, CHILD_MUL_ADD %d, %d MULT18X18D, CHILD_LATENCY %d\n",
                multipliers_name(pc.child_fabric()), c.dir_bits + 1, c.box_bits + 1, pc.child_mul_add(),
                pc.child_dsp_blocks(), pc.child_latency());
    std::printf("  MULT18X18D      %d\n", pc.dsp_blocks());
    std::printf("  LATENCY         %d\n", pc.latency());
    std::printf("  FIFO_DEPTH      %d\n", pc.fifo_depth());
    print_ports(pc.ports());
}

int local_contract_command(const Args& a) {
    using LL = LocalContractLimits;
    LocalRtlConfig c;
    c.box_bits = static_cast<int>(a.get_int("box-bits", c.box_bits, LL::kMinBoxBits, LL::kMaxBoxBits));
    c.dir_bits = static_cast<int>(a.get_int("dir-bits", c.dir_bits, LL::kMinDirBits, LL::kMaxDirBits));
    c.grid_bits = static_cast<int>(a.get_int("grid-bits", c.grid_bits, c.box_bits + LL::kGridMargin, LL::kMaxGridBits));
    c.children = static_cast<int>(a.get_int("children", c.children, 1, LL::kMaxChildren));
    c.tag_bits = static_cast<int>(a.get_int("tag-bits", c.tag_bits, LL::kMinTagBits, 64));
    if (a.has("coord-bits") || a.has("pipeline"))
        throw InputError("options --coord-bits and --pipeline are the global unit's, not --local's");
    try {
        if (a.has("mode")) c.conservative = parse_fixed_mode(a.get("mode", "")) == FixedMode::Conservative;
    } catch (const InputError& e) {
        throw InputError(std::string("option --mode: ") + e.what());
    }
    try {
        if (a.has("mul-style")) c.mul_style = parse_mul_style(a.get("mul-style", ""));
    } catch (const InputError& e) {
        throw InputError(std::string("option --mul-style: ") + e.what());
    }
    print_local_contract(LocalPortContract(c));
    return 0;
}

void print_float_contract(const FloatPortContract& pc) {
    const FloatRtlConfig& c = pc.config();
    std::printf("%s: TAG_BITS %d, CONSERVATIVE %d, MUL_DSP %d\n", pc.module(), c.tag_bits, c.conservative ? 1 : 0,
                c.mul_dsp);
    std::printf("  adders        %d (pluecker_f32_add, latency %d)\n", pc.adders(), FloatLimits::kAddLatency);
    std::printf("  multipliers   %d (pluecker_f32_mul, latency %d), %d MULT18X18D\n", pc.multipliers(),
                FloatLimits::kMulLatency, pc.dsp_blocks());
    std::printf("  LATENCY       %d\n", pc.latency());
    std::printf("  FIFO_DEPTH    %d\n", pc.fifo_depth());
    print_ports(pc.ports());
}

}  // namespace

int cmd_contract(const std::vector<std::string>& argv) {
    const Args a(argv,
                 {"coord-bits", "dir-bits", "tag-bits", "mode", "mul-style", "pipeline", "write", "check", "box-bits",
                  "grid-bits", "children", "unit", "mul-dsp"},
                 {"help", "local"});
    if (a.has("help")) {
        std::fputs(kUsage, stdout);
        return 0;
    }
    if (!a.positional().empty()) throw InputError("unexpected argument '" + a.positional().front() + "'");
    if (a.has("write") && a.has("check")) throw InputError("options --write and --check exclude each other");
    if (a.has("write")) return write_or_check(a.get("write", ""), true);
    if (a.has("check")) return write_or_check(a.get("check", ""), false);
    if (a.has("unit")) {
        if (a.has("local")) throw InputError("options --unit and --local exclude each other");
        FloatRtlConfig f;
        try {
            f.unit = parse_float_unit(a.get("unit", ""));
        } catch (const InputError& e) {
            throw InputError(std::string("option --unit: ") + e.what());
        }
        f.tag_bits = static_cast<int>(a.get_int("tag-bits", ContractDefaults::kTagBits, FloatLimits::kMinTagBits, 64));
        f.mul_dsp = static_cast<int>(a.get_int("mul-dsp", FloatLimits::kDefaultMulDsp, 1, 4));
        try {
            if (a.has("mode")) f.conservative = parse_fixed_mode(a.get("mode", "")) == FixedMode::Conservative;
        } catch (const InputError& e) {
            throw InputError(std::string("option --mode: ") + e.what());
        }
        print_float_contract(FloatPortContract(f));
        return 0;
    }
    if (a.has("local")) return local_contract_command(a);
    for (const char* opt : {"box-bits", "grid-bits", "children"})
        if (a.has(opt)) throw InputError(std::string("option --") + opt + " needs --local");
    RtlConfig c;
    c.coord_bits = static_cast<int>(
        a.get_int("coord-bits", ContractDefaults::kCoordBits, ContractLimits::kMinBits, ContractLimits::kMaxBits));
    c.dir_bits = static_cast<int>(
        a.get_int("dir-bits", ContractDefaults::kDirBits, ContractLimits::kMinBits, ContractLimits::kMaxBits));
    c.tag_bits = static_cast<int>(a.get_int("tag-bits", ContractDefaults::kTagBits, ContractLimits::kMinTagBits, 64));
    c.pipeline = static_cast<int>(a.get_int("pipeline", 0, 0, ContractLimits::kMaxPipeline));
    try {
        if (a.has("mode")) c.conservative = parse_fixed_mode(a.get("mode", "")) == FixedMode::Conservative;
    } catch (const InputError& e) {
        throw InputError(std::string("option --mode: ") + e.what());
    }
    try {
        if (a.has("mul-style")) c.mul_style = parse_mul_style(a.get("mul-style", ""));
    } catch (const InputError& e) {
        throw InputError(std::string("option --mul-style: ") + e.what());
    }
    print_contract(PortContract(c));
    return 0;
}

}  // namespace pluecker::cli
