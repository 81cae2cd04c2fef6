// SPDX-License-Identifier: MIT
// The port contract of the binary32 units, rtl/pluecker_float_intersector.sv
// (the Plücker test, unit "float") and rtl/pluecker_smits_intersector.sv (the
// slab test, unit "smits"): the sibling of contract.hpp for the fixed-point
// intersector, in the same style. It states what the RTL takes (parameters
// and their limits, ports, the encoding of a query) and every constant it
// derives (LATENCY, FIFO depth, MULT18X18D per unit), and carries them to
// the RTL and the scripts through two generated files.
//
// ---------------------------------------------------------------------------
// Parameters (FloatRtlConfig; the RTL refuses anything else at elaboration)
//   TAG_BITS          >= 1
//   CONSERVATIVE      0 or 1 (unit "float" only): outward rounding
//   MUL_DSP           1, 3 or 4: MULT18X18D per 24 x 24 significand product
//                     (pluecker_f32_mant_mul; the other partial products in
//                     fabric)
//
// Derived constants (FloatPortContract), as the RTL derives them
//   ADD_LATENCY = 8, MUL_LATENCY = 7 (pluecker_f32_add, pluecker_f32_mul)
//   float:  LATENCY = 1 + ADD_LATENCY + MUL_LATENCY + 2 = 18 (S0, adders,
//           multipliers, edge comparisons, FIFO write), 6 adders, 12
//           multipliers
//   smits:  LATENCY = 1 + ADD_LATENCY + MUL_LATENCY + 3 + 1 = 20 (S0,
//           adders, multipliers, three bound stages, FIFO write), 6 adders,
//           6 multipliers
//   FIFO_DEPTH        the smallest power of two >= LATENCY + 2
//   MULT18X18D        multipliers x MUL_DSP
//
// Ports (float_port_list): every data field an IEEE-754 binary32 bit
// pattern, x in bits [31:0], then y, then z.
//
// Generated files: float_contract_sv_package() is
// rtl/pluecker_contract_float_pkg.sv (the constants the units check at
// elaboration) and float_contract_json() is rtl/pluecker_contract_float.json
// (the same for scripts/contract.py: synth.py, lint.sh, sim/build.sh, the
// report). `pluecker contract --write rtl` writes them with the fixed-point
// contract's; the test FloatContract.GeneratedFilesAreCurrent fails when a
// committed copy differs.
// ---------------------------------------------------------------------------
#pragma once

#include "pluecker/contract.hpp"
#include "pluecker/f32unit.hpp"

#include <string>
#include <string_view>
#include <vector>

namespace pluecker {

enum class FloatUnit { Pluecker, Smits };

// "float" and "smits": the names of the units in scripts and make targets.
const char* float_unit_name(FloatUnit u);
// The RTL module: pluecker_float_intersector, pluecker_smits_intersector.
const char* float_unit_module(FloatUnit u);

struct FloatLimits {
    static constexpr int kMinTagBits = 1;
    static constexpr int kAddLatency = 8;   // pluecker_f32_add
    static constexpr int kMulLatency = 7;   // pluecker_f32_mul
    static constexpr int kMulDspValues[] = {1, 3, 4};
    static constexpr int kDefaultMulDsp = 4;
};

struct FloatRtlConfig {
    FloatUnit unit = FloatUnit::Pluecker;
    int tag_bits = ContractDefaults::kTagBits;
    bool conservative = false;
    int mul_dsp = FloatLimits::kDefaultMulDsp;
};

// Throws InputError naming the parameter when the RTL would refuse it.
void validate_float_config(const FloatRtlConfig& c);

class FloatPortContract {
public:
    explicit FloatPortContract(const FloatRtlConfig& config);

    const FloatRtlConfig& config() const { return config_; }
    const char* module() const { return float_unit_module(config_.unit); }
    int adders() const { return 6; }
    int multipliers() const;
    int latency() const;
    int fifo_depth() const;
    int dsp_blocks() const { return multipliers() * config_.mul_dsp; }

    const std::vector<PortSpec>& ports() const { return ports_; }
    const PortSpec& port(std::string_view name) const;  // InputError for a name that is not a port

private:
    FloatRtlConfig config_;
    std::vector<PortSpec> ports_;
};

// The LATENCY and FIFO depth of a unit (they depend on nothing else).
int float_latency(FloatUnit u);
int float_fifo_depth(FloatUnit u);

// One input port's value: up to 96 bits in the PortWords of contract.hpp.
struct FloatPortValue {
    std::string name;
    PortWords value{};
};

// The input port values of one query (every port but the handshake and
// the tag), in the order of the port list.
std::vector<FloatPortValue> pack_float_query(const F32PlueckerQuery& q);
std::vector<FloatPortValue> pack_float_query(const F32SmitsQuery& q);

// rtl/pluecker_contract_float_pkg.sv and rtl/pluecker_contract_float.json.
std::string float_contract_sv_package();
std::string float_contract_json();
inline constexpr const char* kFloatContractSvFile = "pluecker_contract_float_pkg.sv";
inline constexpr const char* kFloatContractJsonFile = "pluecker_contract_float.json";

}  // namespace pluecker
