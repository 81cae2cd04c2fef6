// SPDX-License-Identifier: MIT
// The port contract of the binary32 units (float_contract.hpp): the derived
// constants, the port encoding of a query and the generated files.
#include "pluecker/float_contract.hpp"

#include <sstream>

namespace pluecker {
namespace {

using L = FloatLimits;
using f32::Bits;

constexpr FloatUnit kUnits[] = {FloatUnit::Pluecker, FloatUnit::Smits};

bool mul_dsp_ok(int m) {
    for (int v : L::kMulDspValues)
        if (v == m) return true;
    return false;
}

std::string mul_dsp_list() {
    std::string s;
    for (int v : L::kMulDspValues) s += (s.empty() ? "" : ", ") + std::to_string(v);
    return s;
}

PortWords word3(const std::array<Bits, 3>& v) { return {v[0], v[1], v[2]}; }
PortWords word1(std::uint32_t v) { return {v, 0, 0}; }

std::vector<PortSpec> port_list(FloatUnit u, int tag_bits) {
    using D = PortDir;
    std::vector<PortSpec> p = {
        {"clk_i", D::In, 1, 1, false},        {"rst_i", D::In, 1, 1, false},
        {"in_valid_i", D::In, 1, 1, false},   {"in_ready_o", D::Out, 1, 1, false},
        {"in_tag_i", D::In, 1, tag_bits, false}, {"ray_class_i", D::In, 3, 1, false},
        {"ray_org_i", D::In, 3, 32, false},
    };
    if (u == FloatUnit::Pluecker) {
        p.push_back({"ray_dir_i", D::In, 3, 32, false});
        p.push_back({"ray_end_i", D::In, 3, 32, false});
        p.push_back({"ray_end_valid_i", D::In, 1, 1, false});
    } else {
        p.push_back({"ray_inv_i", D::In, 3, 32, false});
        p.push_back({"ray_tmax_i", D::In, 1, 32, false});
    }
    p.push_back({"box_min_i", D::In, 3, 32, false});
    p.push_back({"box_max_i", D::In, 3, 32, false});
    p.push_back({"out_valid_o", D::Out, 1, 1, false});
    p.push_back({"out_ready_i", D::In, 1, 1, false});
    p.push_back({"out_tag_o", D::Out, 1, tag_bits, false});
    p.push_back({"out_hit_o", D::Out, 1, 1, false});
    return p;
}

int multipliers_of(FloatUnit u) { return u == FloatUnit::Pluecker ? 12 : 6; }

std::string upper(std::string s) {
    for (char& c : s) c = static_cast<char>(c >= 'a' && c <= 'z' ? c - 'a' + 'A' : c);
    return s;
}

}  // namespace

const char* float_unit_name(FloatUnit u) { return u == FloatUnit::Pluecker ? "float" : "smits"; }

const char* float_unit_module(FloatUnit u) {
    return u == FloatUnit::Pluecker ? "pluecker_float_intersector" : "pluecker_smits_intersector";
}

void validate_float_config(const FloatRtlConfig& c) {
    if (c.tag_bits < L::kMinTagBits)
        throw InputError("TAG_BITS = " + std::to_string(c.tag_bits) + " is below the minimum " +
                         std::to_string(L::kMinTagBits));
    if (!mul_dsp_ok(c.mul_dsp))
        throw InputError("MUL_DSP = " + std::to_string(c.mul_dsp) + " is not one of " + mul_dsp_list());
    if (c.conservative && c.unit != FloatUnit::Pluecker)
        throw InputError(std::string("CONSERVATIVE: ") + float_unit_module(c.unit) + " has no conservative variant");
}

int float_latency(FloatUnit u) {
    // S0, the adders, the multipliers, then the edge comparisons (float) or
    // the three bound stages (smits), and the FIFO write.
    const int tail = u == FloatUnit::Pluecker ? 1 : 3;
    return 1 + L::kAddLatency + L::kMulLatency + tail + 1;
}

int float_fifo_depth(FloatUnit u) {
    int depth = 1;
    while (depth < float_latency(u) + 2) depth <<= 1;
    return depth;
}

FloatPortContract::FloatPortContract(const FloatRtlConfig& config) : config_(config) {
    validate_float_config(config_);
    ports_ = port_list(config_.unit, config_.tag_bits);
}

int FloatPortContract::multipliers() const { return multipliers_of(config_.unit); }
int FloatPortContract::latency() const { return float_latency(config_.unit); }
int FloatPortContract::fifo_depth() const { return float_fifo_depth(config_.unit); }

const PortSpec& FloatPortContract::port(std::string_view name) const {
    for (const PortSpec& p : ports_)
        if (p.name == name) return p;
    throw InputError("'" + std::string(name) + "' is not a port of " + module());
}

std::vector<FloatPortValue> pack_float_query(const F32PlueckerQuery& q) {
    return {{"ray_class_i", word1(q.cls & 7u)}, {"ray_org_i", word3(q.org)},
            {"ray_dir_i", word3(q.dir)},        {"ray_end_i", word3(q.end)},
            {"ray_end_valid_i", word1(q.has_end ? 1 : 0)}, {"box_min_i", word3(q.lo)},
            {"box_max_i", word3(q.hi)}};
}

std::vector<FloatPortValue> pack_float_query(const F32SmitsQuery& q) {
    return {{"ray_class_i", word1(q.cls & 7u)}, {"ray_org_i", word3(q.org)}, {"ray_inv_i", word3(q.inv)},
            {"ray_tmax_i", word1(q.tmax)},      {"box_min_i", word3(q.lo)},  {"box_max_i", word3(q.hi)}};
}

std::string float_contract_sv_package() {
    std::ostringstream s;
    s << "// SPDX-License-Identifier: MIT\n"
         "// Generated from model/core/src/float_contract.cpp by `pluecker contract --write rtl`:\n"
         "// do not edit (the test FloatContract.GeneratedFilesAreCurrent compares this file).\n"
         "//\n"
         "// The port contract of the binary32 units pluecker_float_intersector and\n"
         "// pluecker_smits_intersector (model/core/include/pluecker/float_contract.hpp):\n"
         "// the limits they check and the constants they must derive; elaboration fails\n"
         "// when a unit's LATENCY or FIFO_DEPTH, or a primitive's latency, differs.\n"
         "package pluecker_contract_float_pkg;\n"
         "  localparam int MIN_TAG_BITS = " << L::kMinTagBits << ";\n"
         "  // Latencies of pluecker_f32_add and pluecker_f32_mul.\n"
         "  localparam int ADD_LATENCY = " << L::kAddLatency << ";\n"
         "  localparam int MUL_LATENCY = " << L::kMulLatency << ";\n"
         "  // MULT18X18D per significand product when MUL_DSP is not given.\n"
         "  localparam int DEFAULT_MUL_DSP = " << L::kDefaultMulDsp << ";\n";
    for (FloatUnit u : kUnits) {
        const std::string n = upper(float_unit_name(u));
        s << "  // " << float_unit_module(u) << "\n"
          << "  localparam int " << n << "_LATENCY = " << float_latency(u) << ";\n"
          << "  localparam int " << n << "_FIFO_DEPTH = " << float_fifo_depth(u) << ";\n"
          << "  localparam int " << n << "_MULTIPLIERS = " << multipliers_of(u) << ";\n";
    }
    s << "\n  // MUL_DSP values the units take.\n"
         "  function automatic bit mul_dsp_ok(input int m);\n"
         "    mul_dsp_ok = ";
    bool first = true;
    for (int v : L::kMulDspValues) {
        s << (first ? "" : " || ") << "m == " << v;
        first = false;
    }
    s << ";\n  endfunction\nendpackage\n";
    return s.str();
}

std::string float_contract_json() {
    std::ostringstream s;
    s << "{\n"
         "  \"generated_by\": \"pluecker contract --write rtl (model/core/src/float_contract.cpp); do not edit\",\n"
         "  \"limits\": {\"tag_bits_min\": " << L::kMinTagBits << ", \"mul_dsp\": [" << mul_dsp_list() << "]},\n"
      << "  \"defaults\": {\"tag_bits\": " << ContractDefaults::kTagBits << ", \"conservative\": 0, \"mul_dsp\": "
      << L::kDefaultMulDsp << "},\n"
      << "  \"add_latency\": " << L::kAddLatency << ", \"mul_latency\": " << L::kMulLatency << ",\n"
      << "  \"units\": [\n";
    for (std::size_t k = 0; k < std::size(kUnits); ++k) {
        const FloatUnit u = kUnits[k];
        FloatRtlConfig c;
        c.unit = u;
        const FloatPortContract pc(c);
        s << "    {\"unit\": \"" << float_unit_name(u) << "\", \"module\": \"" << float_unit_module(u)
          << "\", \"latency\": " << pc.latency() << ", \"fifo_depth\": " << pc.fifo_depth()
          << ", \"adders\": " << pc.adders() << ", \"multipliers\": " << pc.multipliers()
          << ", \"conservative\": " << (u == FloatUnit::Pluecker ? "[0, 1]" : "[0]") << ",\n"
          << "     \"mult18x18d\": {";
        bool first = true;
        for (int m : L::kMulDspValues) {
            s << (first ? "" : ", ") << "\"" << m << "\": " << pc.multipliers() * m;
            first = false;
        }
        s << "},\n     \"ports\": [";
        first = true;
        for (const PortSpec& p : pc.ports()) {
            s << (first ? "" : ", ") << "[\"" << p.name << "\", \"" << (p.dir == PortDir::In ? "in" : "out")
              << "\", ";
            if (p.name.find("_tag_") != std::string::npos)
                s << "\"TAG_BITS\"";  // the parameter's width
            else
                s << p.width();
            s << "]";
            first = false;
        }
        s << "]}" << (k + 1 < std::size(kUnits) ? "," : "") << "\n";
    }
    s << "  ]\n}\n";
    return s.str();
}

}  // namespace pluecker
