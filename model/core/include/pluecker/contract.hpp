// SPDX-License-Identifier: MIT
// The port contract of rtl/pluecker_intersector.sv: what the RTL takes (its
// parameters and their limits, its ports and the encoding of a query on
// them) and every constant it derives from its parameters (multiplier style,
// adder stages, LATENCY, FIFO depth). Every layer that drives the RTL reads
// it from here: the fixed-point format (FixedFormat's width limits), the
// Python binding (PortContract, rtl_ports), the Verilator harness
// (pack_query, the latency it checks) and, through two generated files, the
// RTL itself, the formal harness and the scripts.
//
// ---------------------------------------------------------------------------
// Parameters (RtlConfig; the RTL refuses anything else at elaboration)
//   COORD_BITS = C, DIR_BITS = D   6..24 each (ContractLimits::kMinBits..kMaxBits)
//   TAG_BITS                       >= 1
//   CONSERVATIVE                   1 (margin) or 0 (nearest)
//   MUL_STYLE                      "auto" | "dsp" | "lut" | "rom"
//   PIPELINE                       0..2: the multipliers' extra registers (1:
//                                   the MULT18X18D pipeline register, in
//                                   fabric a cut across the adder tree; 2:
//                                   also a fabric register after every
//                                   product, so the route out of a DSP
//                                   column gets a whole period)
//
// Derived constants (PortContract), exactly as the RTL derives them
//   WA = C + 1, WB = D + 1          multiplier operands (signed A_i / B_j, D_i)
//   fabric multipliers              MUL_STYLE "lut", or "auto" with C <= 9 and
//                                   D <= 9 (kMulLutMaxBits); else MULT18X18D
//   MUL_ADD = (WA > 18) + (WB > 18) registered adder stages that sum the
//                                   partial products of a split DSP operand
//                                   (kDspOperandBits = 18); "lut" needs 0
//   S2X = PIPELINE + MUL_ADD        stages between S2 and S3
//   LATENCY = 6 + S2X               input handshake to the earliest output
//                                   handshake (S0..S4 and the FIFO write)
//   FIFO_DEPTH                      the smallest power of two >= LATENCY + 2
//   paired products                 DSP multipliers, PIPELINE = 2 and
//                                   C + 2 D <= 18 (6/6): one MULT18X18D
//                                   does both products of a difference
//                                   (rtl/pluecker_mul_pair.sv)
//   MULT18X18D per unit             0 with fabric or table multipliers, 6
//                                   with paired products, else
//                                   12 (1 + (WA > 18)) (1 + (WB > 18))
//   table multipliers               MUL_STYLE "rom": every product looked up
//                                   in one block RAM (DP16KD, both ports;
//                                   rtl/pluecker_mul_rom.sv); needs
//                                   PIPELINE = 2 and WA + ceil(D/2) <= 10
//                                   (kRomAddressBits: one 1K x 18 port),
//                                   i.e. 6/6 bits
//   DP16KD per unit                 12 with table multipliers, else 0
//
// Ports (port_list): x in the low field, then y, then z; coordinates
// (origin, segment end, box planes) C-bit two's complement, directions D-bit
// unsigned magnitudes, ray_class_i bit a set = axis a negative.
//
// One source across languages: contract_sv_package() is
// rtl/pluecker_contract_pkg.sv (the limits and the class table the RTL reads;
// it checks at elaboration that what it derives equals the table's row) and
// contract_json() is rtl/pluecker_contract.json (the same table, read by
// scripts/contract.py for synth.py, lint.sh, the formal run and
// sim/build.sh). `pluecker contract --write rtl` regenerates both; the test
// Contract.GeneratedFilesAreCurrent fails when a committed copy differs.
// ---------------------------------------------------------------------------
#pragma once

#include <array>
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

namespace pluecker {

struct FixedFormat;
struct FixedRay;
struct FixedBox;

struct ContractLimits {
    static constexpr int kMinBits = 6;   // COORD_BITS, DIR_BITS
    static constexpr int kMaxBits = 24;
    static constexpr int kMinTagBits = 1;
    static constexpr int kMaxPipeline = 2;
    // A MULT18X18D operand; a wider multiplier operand is split in two.
    static constexpr int kDspOperandBits = 18;
    // MUL_STYLE "auto" builds the multipliers in fabric when both widths are
    // at most this (measured: more box tests per second per chip there).
    static constexpr int kMulLutMaxBits = 9;
    // MUL_STYLE "rom": address bits of one block-RAM read port (1K x 18).
    static constexpr int kRomAddressBits = 10;
    // S0..S4 and the FIFO write, without S2x stages.
    static constexpr int kBaseLatency = 6;
    // Products B_j*D_i and A_i*D_j of the six edge tests.
    static constexpr int kProducts = 12;
};

// The RTL's parameter defaults.
struct ContractDefaults {
    static constexpr int kCoordBits = 16;
    static constexpr int kDirBits = 16;
    static constexpr int kTagBits = 16;
};

enum class MulStyle { Auto, Dsp, Lut, Rom };

const char* mul_style_name(MulStyle s);

// One configuration of rtl/pluecker_intersector.sv (its parameters).
struct RtlConfig {
    int coord_bits = ContractDefaults::kCoordBits;
    int dir_bits = ContractDefaults::kDirBits;
    int tag_bits = ContractDefaults::kTagBits;
    bool conservative = true;
    MulStyle mul_style = MulStyle::Auto;
    int pipeline = 0;
};

enum class PortDir { In, Out };

struct PortSpec {
    std::string name;
    PortDir dir = PortDir::In;
    int fields = 1;      // 3 for per-axis vectors (x in the low field)
    int field_bits = 1;  // bits of one field
    bool is_signed = false;
    int width() const { return fields * field_bits; }
    int field_lsb(int field) const { return field * field_bits; }
};

// The derived constants of one configuration. The constructor throws
// InputError for every configuration the RTL refuses at elaboration.
class PortContract {
public:
    explicit PortContract(const RtlConfig& config);

    const RtlConfig& config() const { return config_; }
    // The fixed-point format the configuration computes (widths and mode).
    FixedFormat format() const;

    int mul_a_bits() const { return config_.coord_bits + 1; }  // WA
    int mul_b_bits() const { return config_.dir_bits + 1; }    // WB
    bool fabric_multipliers() const { return fabric_; }
    int mul_add() const { return mul_add_; }
    int s2x_stages() const { return config_.pipeline + mul_add_; }
    int latency() const { return ContractLimits::kBaseLatency + s2x_stages(); }
    int fifo_depth() const;
    bool paired_products() const;  // two products per MULT18X18D
    int dsp_blocks() const;  // MULT18X18D of one intersector
    bool rom_multipliers() const { return config_.mul_style == MulStyle::Rom; }
    int rom_blocks() const;  // DP16KD of one intersector (its table multipliers)

    // Every port of the module, in declaration order.
    const std::vector<PortSpec>& ports() const { return ports_; }
    // InputError for a name that is not a port.
    const PortSpec& port(std::string_view name) const;

private:
    RtlConfig config_;
    bool fabric_ = false;
    int mul_add_ = 0;
    std::vector<PortSpec> ports_;
};

// Throws InputError naming the parameter, with the RTL's rule, when the RTL
// would refuse the configuration.
void validate_rtl_config(const RtlConfig& config);

// ---------------------------------------------------------------------------
// The encoding of one query on the input ports
// ---------------------------------------------------------------------------

// A port value of up to 3 * kMaxBits = 72 bits, least significant word
// first; bits above the port's width are zero.
using PortWords = std::array<std::uint32_t, 3>;

struct QueryPorts {
    std::uint32_t ray_class = 0;  // ray_class_i
    PortWords ray_org{};          // ray_org_i
    PortWords ray_dir{};          // ray_dir_i
    PortWords ray_end{};          // ray_end_i (as given, also when ray_end_valid is 0)
    std::uint32_t ray_end_valid = 0;
    PortWords box_min{};          // box_min_i
    PortWords box_max{};          // box_max_i
};

// Throws InputError naming the operand (e.g. "ray origin x = 40 does not fit
// COORD_BITS = 6 (range -32..31)") when a value does not fit its port: the
// class outside 0..7, a coordinate outside C-bit two's complement, a
// direction outside 0..2^D - 1 (the RTL computes every such value exactly;
// the set-up produces at most 2^(D-1)).
void check_query_operands(const FixedRay& r, const FixedBox& b, const FixedFormat& f);
// The port values of one query (checked as above).
QueryPorts pack_query(const FixedRay& r, const FixedBox& b, const FixedFormat& f);
// The inverse of pack_query: coordinates sign-extended from C bits.
void unpack_query(const QueryPorts& p, const FixedFormat& f, FixedRay& r, FixedBox& b);

// ---------------------------------------------------------------------------
// The contract as a table, and the generated files
// ---------------------------------------------------------------------------

// A configuration class: a rectangle of width pairs with one style and
// PIPELINE value over which every derived constant is the same. The classes
// partition all supported configurations (widths split where any derived
// constant changes).
struct ContractClass {
    int coord_lo = 0, coord_hi = 0;
    int dir_lo = 0, dir_hi = 0;
    MulStyle mul_style = MulStyle::Auto;
    int pipeline = 0;
    bool fabric = false;
    int mul_add = 0;
    int s2x_stages = 0;
    int latency = 0;
    int fifo_depth = 0;
    int dsp_blocks = 0;
    bool rom = false;  // table multipliers (MUL_STYLE "rom")
    int rom_blocks = 0;
};

std::vector<ContractClass> contract_classes();

// rtl/pluecker_contract_pkg.sv and rtl/pluecker_contract.json.
std::string contract_sv_package();
std::string contract_json();
inline constexpr const char* kContractSvFile = "pluecker_contract_pkg.sv";
inline constexpr const char* kContractJsonFile = "pluecker_contract.json";

}  // namespace pluecker
