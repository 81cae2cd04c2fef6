// SPDX-License-Identifier: MIT
// The port contract of rtl/pluecker_local_intersector.sv, the local-frame
// unit (local.hpp), in the style of contract.hpp: what the RTL takes (its
// parameters and their limits, its ports and the encoding of a query on
// them) and every constant it derives (multiplier styles, adder stages,
// LATENCY, FIFO depth, MULT18X18D count). The Python binding
// (LocalPortContract, local_rtl_ports), the Verilator harness and, through
// two generated files, the RTL and the scripts read it from here.
//
// ---------------------------------------------------------------------------
// Parameters (LocalRtlConfig; the RTL refuses anything else at elaboration)
//   BOX_BITS = K    4..16 (LocalFormat's limits)
//   DIR_BITS = D    4..24 (LocalFormat's limits)
//   GRID_BITS = G   K+2..32: the model takes up to 48; the RTL's moment
//                   products are (G+3) x (G+1) bits and pluecker_mul takes
//                   operands of at most 35 bits
//   TAG_BITS        >= 1
//   CONSERVATIVE    1 (margin) or 0 (nearest)
//   MUL_STYLE       "auto" | "dsp" | "lut"
//   CHILDREN        1..2: child boxes per query, one node set-up
//   EXP_BITS        $clog2(G - K + 2): one frame exponent, 0..G-K+1
//
// Derived constants (LocalPortContract), exactly as the RTL derives them
//   fabric moment products          MUL_STYLE "lut"
//   fabric child products           MUL_STYLE "auto" or "lut"
//   FRAME_MUL_ADD                   0 in fabric, else (G+3 > 18) + (G+1 > 18)
//   CHILD_MUL_ADD                   0 in fabric, else (D+1 > 18) + (K+1 > 18)
//   FRAME_LATENCY = 9 + FRAME_MUL_ADD  register stages of the node set-up
//   CHILD_LATENCY = 4 + CHILD_MUL_ADD  register stages of a child
//   LATENCY = FRAME_LATENCY + CHILD_LATENCY + 1   input handshake to the
//                                   earliest output handshake
//   FIFO_DEPTH                      the smallest power of two >= LATENCY + 2
//   MULT18X18D                      node set-up 6 (1 + (G+3 > 18)) (1 + (G+1 > 18))
//                                   unless fabric, plus per child 12 (1 + (D+1 > 18))
//                                   (1 + (K+1 > 18)) with "dsp"
//
// Ports (local_port_list): x in the low field, then y, then z; the boxes
// of child c in fields 3c..3c+2 of box_min_i and box_max_i.
//
// Operands (check_local_query_operands): the class 0..7; origin, end and
// frame origin G-bit two's complement; DG unsigned with its largest
// component exactly 2^(G-1) and none above (local_setup_ray's direction:
// the node set-up's scaling c assumes it); exponents 0..G-K+1; box offsets
// 0..2^K - 1 (any, also LO > HI). The RTL computes every such query as the
// model does; other values of DG and the exponents are outside the
// contract (the RTL's answer is not specified).
//
// One source across languages: local_contract_sv_package() is
// rtl/pluecker_local_contract_pkg.sv and local_contract_json() is
// rtl/pluecker_local_contract.json; `pluecker contract --write rtl` writes
// them with the global unit's, the test
// LocalContract.GeneratedFilesAreCurrent fails when a committed copy differs.
// ---------------------------------------------------------------------------
#pragma once

#include "pluecker/contract.hpp"
#include "pluecker/local.hpp"

#include <span>
#include <string>
#include <string_view>
#include <vector>

namespace pluecker {

struct LocalContractLimits {
    static constexpr int kMinBoxBits = LocalFormat::kMinBoxBits;
    static constexpr int kMaxBoxBits = LocalFormat::kMaxBoxBits;
    static constexpr int kMinDirBits = LocalFormat::kMinDirBits;
    static constexpr int kMaxDirBits = LocalFormat::kMaxDirBits;
    // GRID_BITS >= BOX_BITS + kGridMargin (LocalFormat's rule).
    static constexpr int kGridMargin = 2;
    static constexpr int kMaxGridBits = 32;
    static constexpr int kMinGridBits = kMinBoxBits + kGridMargin;
    static constexpr int kMinTagBits = 1;
    static constexpr int kMaxChildren = 2;
    static constexpr int kDspOperandBits = ContractLimits::kDspOperandBits;
    // Register stages of the node set-up and of a child without adder stages.
    static constexpr int kFrameBaseLatency = 9;
    static constexpr int kChildBaseLatency = 4;
    static constexpr int kMomentProducts = 6;
    static constexpr int kChildProducts = 12;
};

// The RTL's parameter defaults.
struct LocalContractDefaults {
    static constexpr int kBoxBits = 8;
    static constexpr int kDirBits = 11;
    static constexpr int kGridBits = 32;
    static constexpr int kTagBits = 16;
    static constexpr int kChildren = 1;
};

// One configuration of rtl/pluecker_local_intersector.sv (its parameters).
struct LocalRtlConfig {
    int box_bits = LocalContractDefaults::kBoxBits;
    int dir_bits = LocalContractDefaults::kDirBits;
    int grid_bits = LocalContractDefaults::kGridBits;
    int tag_bits = LocalContractDefaults::kTagBits;
    bool conservative = true;
    MulStyle mul_style = MulStyle::Auto;
    int children = LocalContractDefaults::kChildren;
};

// Throws InputError naming the parameter, with the RTL's rule, when the RTL
// would refuse the configuration.
void validate_local_rtl_config(const LocalRtlConfig& config);

// $clog2(G - K + 2): the bits of one frame exponent.
int local_exp_bits(int grid_bits, int box_bits);

// The derived constants and ports of one configuration. The constructor
// throws InputError for every configuration the RTL refuses.
class LocalPortContract {
public:
    explicit LocalPortContract(const LocalRtlConfig& config);

    const LocalRtlConfig& config() const { return config_; }
    // The local format of the configuration (widths and mode).
    LocalFormat format() const;

    int exp_bits() const { return local_exp_bits(config_.grid_bits, config_.box_bits); }
    bool frame_fabric() const;  // moment products in fabric
    bool child_fabric() const;  // child products in fabric
    int frame_mul_add() const;
    int child_mul_add() const;
    int frame_latency() const { return LocalContractLimits::kFrameBaseLatency + frame_mul_add(); }
    int child_latency() const { return LocalContractLimits::kChildBaseLatency + child_mul_add(); }
    int latency() const { return frame_latency() + child_latency() + 1; }
    int fifo_depth() const;
    int frame_dsp_blocks() const;  // MULT18X18D of the node set-up
    int child_dsp_blocks() const;  // MULT18X18D of one child
    int dsp_blocks() const { return frame_dsp_blocks() + config_.children * child_dsp_blocks(); }

    // Every port of the module, in declaration order.
    const std::vector<PortSpec>& ports() const { return ports_; }
    // InputError for a name that is not a port.
    const PortSpec& port(std::string_view name) const;

private:
    LocalRtlConfig config_;
    std::vector<PortSpec> ports_;
};

// ---------------------------------------------------------------------------
// The encoding of one query on the input ports (port values as contract.hpp's
// PortWords: 32-bit words, least significant first; every port here is at
// most 3 x 32 = 96 bits)
// ---------------------------------------------------------------------------

struct LocalQueryPorts {
    std::uint32_t ray_class = 0;  // ray_class_i
    PortWords ray_org{};          // ray_org_i
    PortWords ray_dir{};          // ray_dir_i (DG)
    PortWords ray_end{};          // ray_end_i (as given, also when ray_end_valid is 0)
    std::uint32_t ray_end_valid = 0;
    PortWords frame_org{};        // frame_org_i
    std::uint32_t frame_exp = 0;  // frame_exp_i (3 x EXP_BITS <= 15 bits)
    PortWords box_min{};          // box_min_i (CHILDREN x 3 fields)
    PortWords box_max{};          // box_max_i
};

// The operand rules one by one (InputError naming the operand): a ray as
// local_setup_ray gives it (class 0..7, origin and end on the grid, DG
// 0..2^(G-1) with the largest exactly 2^(G-1)), a frame (check_frame of
// local.hpp), a box's offsets in 0..2^K - 1 (`what` names it).
void check_local_ray(const LocalRay& r, const LocalFormat& f);
void check_local_box(const LocalBox& b, const LocalFormat& f, const std::string& what = "box");

// Throws InputError naming the operand (e.g. "frame exponent y = 30 is
// outside 0..25 (GRID_BITS - BOX_BITS + 1)") when a value is outside the
// contract (see the header); boxes.size() must be the configuration's
// CHILDREN.
void check_local_query_operands(const LocalRay& r, const LocalFrame& fr, std::span<const LocalBox> boxes,
                                const LocalPortContract& c);
// The port values of one query (checked as above).
LocalQueryPorts pack_local_query(const LocalRay& r, const LocalFrame& fr, std::span<const LocalBox> boxes,
                                 const LocalPortContract& c);
// The inverse of pack_local_query (the LocalRay's `clipped` is false).
void unpack_local_query(const LocalQueryPorts& p, const LocalPortContract& c, LocalRay& r, LocalFrame& fr,
                        std::vector<LocalBox>& boxes);

// ---------------------------------------------------------------------------
// The node ray between the unit's two parts: the outputs of
// rtl/pluecker_local_frame.sv and the inputs of rtl/pluecker_local_child.sv
//   cls        3 bits            dir  3 x D bits unsigned
//   w          6 x (K+D+2) bits signed, pair order k = 0..5 (local_pair_i/j)
//   org, end   3 x (K+2) bits signed            end_valid  1 bit
// ---------------------------------------------------------------------------

// Up to 6 x 42 = 252 bits (the w field), least significant word first.
using NodeRayWords = std::array<std::uint32_t, 8>;

struct LocalNodeRayPorts {
    std::uint32_t cls = 0;
    PortWords dir{};
    NodeRayWords w{};
    PortWords org{};
    PortWords end{};  // zero fields when the node ray has no end
    std::uint32_t end_valid = 0;
};

// Boxes on box_min_i / box_max_i (of the unit: child c in fields
// 3c..3c+2; of pluecker_local_child: one box); InputError for an offset
// outside 0..2^K - 1.
struct LocalBoxPorts {
    PortWords box_min{};
    PortWords box_max{};
};
LocalBoxPorts pack_local_boxes(std::span<const LocalBox> boxes, const LocalFormat& f);

// Throws InputError naming the field when a value does not fit its port
// (DIR 0..2^D - 1, W K+D+2 bits signed, ORG and END K+2 bits signed).
void check_local_node_ray(const LocalNodeRay& r, const LocalFormat& f);
LocalNodeRayPorts pack_local_node_ray(const LocalNodeRay& r, const LocalFormat& f);

// ---------------------------------------------------------------------------
// The contract as a table, and the generated files
// ---------------------------------------------------------------------------

// A configuration class: a rectangle of (DIR_BITS, GRID_BITS) with one
// MUL_STYLE over which every derived constant is the same (BOX_BITS and
// CHILDREN change none of them but the MULT18X18D total, given per part).
// GRID_BITS below BOX_BITS + 2 is refused by the RTL's own check.
struct LocalContractClass {
    int dir_lo = 0, dir_hi = 0;
    int grid_lo = 0, grid_hi = 0;
    MulStyle mul_style = MulStyle::Auto;
    bool frame_fabric = false, child_fabric = false;
    int frame_mul_add = 0, child_mul_add = 0;
    int latency = 0;
    int fifo_depth = 0;
    int frame_dsp_blocks = 0, child_dsp_blocks = 0;
};

std::vector<LocalContractClass> local_contract_classes();

// rtl/pluecker_local_contract_pkg.sv and rtl/pluecker_local_contract.json.
std::string local_contract_sv_package();
std::string local_contract_json();
inline constexpr const char* kLocalContractSvFile = "pluecker_local_contract_pkg.sv";
inline constexpr const char* kLocalContractJsonFile = "pluecker_local_contract.json";

}  // namespace pluecker
