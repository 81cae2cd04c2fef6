// SPDX-License-Identifier: MIT
// `pluecker contract`: the port contract of rtl/pluecker_intersector.sv for
// one configuration, and the generated files that carry it to the RTL and
// the scripts (model/core/include/pluecker/contract.hpp).
#include "commands.hpp"
#include "pluecker/app/names.hpp"

#include "pluecker/contract.hpp"
#include "pluecker/fixed.hpp"
#include "pluecker/float_contract.hpp"

#include <cstdio>
#include <fstream>
#include <sstream>
#include <string>

namespace pluecker::cli {

namespace {

constexpr const char* kUsage =
    "usage: pluecker contract [--coord-bits N] [--dir-bits M] [--tag-bits T] [--mode MODE]\n"
    "                         [--mul-style STYLE] [--pipeline P]\n"
    "       pluecker contract --unit float|smits [--tag-bits T] [--mode MODE] [--mul-dsp M]\n"
    "       pluecker contract --write DIR | --check DIR\n"
    "Prints the port contract of rtl/pluecker_intersector.sv for one configuration:\n"
    "the constants the RTL derives from its parameters (multipliers, MUL_ADD, LATENCY,\n"
    "FIFO_DEPTH) and its ports with their fields (x in the low field). With --unit,\n"
    "the contract of a binary32 unit instead (float_contract.hpp): 'float' is\n"
    "rtl/pluecker_float_intersector.sv (--mode conservative: CONSERVATIVE = 1,\n"
    "default nearest), 'smits' rtl/pluecker_smits_intersector.sv; --mul-dsp is MUL_DSP.\n"
    "--write DIR writes the generated files DIR/pluecker_contract_pkg.sv and\n"
    "DIR/pluecker_contract_float_pkg.sv (read by the RTL), DIR/pluecker_contract.json and\n"
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
    "  --mul-dsp M       MUL_DSP of a binary32 unit: 1, 3 or 4            [4]\n";

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
                               {kFloatContractJsonFile, float_contract_json()}};
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
            std::printf(" = 3 x %d%s:", p.field_bits, p.is_signed ? " signed" : "");
            for (int a = 0; a < p.fields; ++a) {
                const int lo = p.field_lsb(a), hi = lo + p.field_bits - 1;
                if (hi == lo)
                    std::printf(" %c [%d]", "xyz"[a], lo);
                else
                    std::printf(" %c [%d:%d]", "xyz"[a], hi, lo);
            }
        }
        std::printf("\n");
    }
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

void print_contract(const PortContract& pc) {
    const RtlConfig& c = pc.config();
    std::printf("COORD_BITS %d, DIR_BITS %d, TAG_BITS %d, CONSERVATIVE %d, MUL_STYLE %s, PIPELINE %d\n",
                c.coord_bits, c.dir_bits, c.tag_bits, c.conservative ? 1 : 0, mul_style_name(c.mul_style),
                c.pipeline);
    std::printf("  multipliers   %s, operands %d x %d bits, %d MULT18X18D\n",
                pc.fabric_multipliers() ? "fabric (pluecker_mul_lut)" : "DSP (pluecker_mul)", pc.mul_a_bits(),
                pc.mul_b_bits(), pc.dsp_blocks());
    std::printf("  MUL_ADD       %d\n", pc.mul_add());
    std::printf("  S2x stages    %d (PIPELINE + MUL_ADD)\n", pc.s2x_stages());
    std::printf("  LATENCY       %d\n", pc.latency());
    std::printf("  FIFO_DEPTH    %d\n", pc.fifo_depth());
    print_ports(pc.ports());
}

}  // namespace

int cmd_contract(const std::vector<std::string>& argv) {
    const Args a(argv, {"coord-bits", "dir-bits", "tag-bits", "mode", "mul-style", "pipeline", "write", "check", "unit",
                        "mul-dsp"},
                 {"help"});
    if (a.has("help")) {
        std::fputs(kUsage, stdout);
        return 0;
    }
    if (!a.positional().empty()) throw InputError("unexpected argument '" + a.positional().front() + "'");
    if (a.has("write") && a.has("check")) throw InputError("options --write and --check exclude each other");
    if (a.has("write")) return write_or_check(a.get("write", ""), true);
    if (a.has("check")) return write_or_check(a.get("check", ""), false);
    if (a.has("unit")) {
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
