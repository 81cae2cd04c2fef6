// SPDX-License-Identifier: MIT
// The port contract of the binary32 units (float_contract.hpp): the derived
// constants, the parameter checks, the ports, the packing of a query, and
// that the committed generated files (rtl/pluecker_contract_float_pkg.sv,
// rtl/pluecker_contract_float.json) are what this build generates.
#include "pluecker/app/names.hpp"  // parse_float_unit
#include "pluecker/f32unit.hpp"
#include "pluecker/float_contract.hpp"

#include <gtest/gtest.h>

#include <fstream>
#include <sstream>
#include <string>

#ifndef PLUECKER_RTL_DIR
#error "PLUECKER_RTL_DIR must name the rtl/ directory (model/CMakeLists.txt)"
#endif

namespace pluecker {
namespace {

FloatPortContract contract(FloatUnit u, int mul_dsp = FloatLimits::kDefaultMulDsp, bool conservative = false,
                           int tag_bits = 16) {
    FloatRtlConfig c;
    c.unit = u;
    c.mul_dsp = mul_dsp;
    c.conservative = conservative;
    c.tag_bits = tag_bits;
    return FloatPortContract(c);
}

TEST(FloatContract, LatencyFifoAndDsp) {
    const FloatPortContract p = contract(FloatUnit::Pluecker);
    EXPECT_EQ(p.latency(), 1 + FloatLimits::kAddLatency + FloatLimits::kMulLatency + 2);
    EXPECT_EQ(p.latency(), 18);
    EXPECT_EQ(p.fifo_depth(), 32);
    EXPECT_EQ(p.multipliers(), 12);
    EXPECT_STREQ(p.module(), "pluecker_float_intersector");
    const FloatPortContract s = contract(FloatUnit::Smits);
    EXPECT_EQ(s.latency(), 20);
    EXPECT_EQ(s.fifo_depth(), 32);
    EXPECT_EQ(s.multipliers(), 6);
    for (int m : FloatLimits::kMulDspValues) {
        EXPECT_EQ(contract(FloatUnit::Pluecker, m).dsp_blocks(), 12 * m);
        EXPECT_EQ(contract(FloatUnit::Smits, m).dsp_blocks(), 6 * m);
    }
    // A power of two with room for one query per clock.
    for (const FloatPortContract& c : {p, s}) {
        EXPECT_GE(c.fifo_depth(), c.latency() + 2);
        EXPECT_LT(c.fifo_depth() / 2, c.latency() + 2);
    }
}

TEST(FloatContract, RefusesWhatTheRtlRefuses) {
    EXPECT_THROW(contract(FloatUnit::Pluecker, 2), InputError);
    EXPECT_THROW(contract(FloatUnit::Pluecker, 0), InputError);
    EXPECT_THROW(contract(FloatUnit::Smits, 5), InputError);
    EXPECT_THROW(contract(FloatUnit::Pluecker, 4, false, 0), InputError);
    EXPECT_THROW(contract(FloatUnit::Smits, 4, true), InputError);  // no conservative slab unit
    EXPECT_NO_THROW(contract(FloatUnit::Pluecker, 1, true, 1));
    try {
        contract(FloatUnit::Smits, 2);
        FAIL();
    } catch (const InputError& e) {
        EXPECT_NE(std::string(e.what()).find("MUL_DSP = 2"), std::string::npos) << e.what();
    }
    EXPECT_EQ(parse_float_unit("float"), FloatUnit::Pluecker);
    EXPECT_EQ(parse_float_unit("smits"), FloatUnit::Smits);
    EXPECT_THROW(parse_float_unit("fixed"), InputError);
}

TEST(FloatContract, Ports) {
    const FloatPortContract p = contract(FloatUnit::Pluecker, 4, false, 9);
    EXPECT_EQ(p.port("in_tag_i").width(), 9);
    EXPECT_EQ(p.port("out_tag_o").width(), 9);
    EXPECT_EQ(p.port("ray_org_i").width(), 96);
    EXPECT_EQ(p.port("ray_dir_i").field_lsb(2), 64);
    EXPECT_EQ(p.port("ray_end_valid_i").width(), 1);
    EXPECT_THROW(p.port("ray_inv_i"), InputError);
    const FloatPortContract s = contract(FloatUnit::Smits);
    EXPECT_EQ(s.port("ray_inv_i").width(), 96);
    EXPECT_EQ(s.port("ray_tmax_i").width(), 32);
    EXPECT_THROW(s.port("ray_dir_i"), InputError);
}

// Every input port but the handshake and the tag gets a value, x in the
// low word, in the order of the port list.
TEST(FloatContract, PackPlacesFields) {
    F32PlueckerQuery q;
    q.cls = 5;
    q.org = {1, 2, 3};
    q.dir = {4, 5, 6};
    q.end = {7, 8, 9};
    q.has_end = true;
    q.lo = {10, 11, 12};
    q.hi = {0xfffffffeu, 14, 15};
    const auto v = pack_float_query(q);
    const FloatPortContract p = contract(FloatUnit::Pluecker);
    std::size_t k = 0;
    for (const PortSpec& port : p.ports()) {
        if (port.dir != PortDir::In || port.name == "clk_i" || port.name == "rst_i" || port.name == "in_valid_i" ||
            port.name == "in_tag_i" || port.name == "out_ready_i")
            continue;
        ASSERT_LT(k, v.size());
        EXPECT_EQ(v[k].name, port.name);
        ++k;
    }
    EXPECT_EQ(k, v.size());
    EXPECT_EQ(v[0].value[0], 5u);
    EXPECT_EQ(v[1].value[0], 1u);
    EXPECT_EQ(v[1].value[2], 3u);
    EXPECT_EQ(v[4].value[0], 1u);
    EXPECT_EQ(v[6].value[0], 0xfffffffeu);
    F32SmitsQuery s;
    s.tmax = 0x7f800000u;
    s.inv = {20, 21, 22};
    const auto w = pack_float_query(s);
    EXPECT_EQ(w[2].name, "ray_inv_i");
    EXPECT_EQ(w[2].value[1], 21u);
    EXPECT_EQ(w[3].name, "ray_tmax_i");
    EXPECT_EQ(w[3].value[0], 0x7f800000u);
    EXPECT_EQ(w[3].value[1], 0u);
}

std::string read_file(const std::string& path) {
    std::ifstream in(path, std::ios::binary);
    EXPECT_TRUE(in) << "cannot read " << path;
    std::ostringstream s;
    s << in.rdbuf();
    return s.str();
}

TEST(FloatContract, GeneratedFilesAreCurrent) {
    const std::string dir = PLUECKER_RTL_DIR;
    EXPECT_EQ(read_file(dir + "/" + kFloatContractSvFile), float_contract_sv_package())
        << dir << "/" << kFloatContractSvFile
        << " is not what the port contract generates: run 'pluecker contract --write rtl' (make contract)";
    EXPECT_EQ(read_file(dir + "/" + kFloatContractJsonFile), float_contract_json())
        << dir << "/" << kFloatContractJsonFile
        << " is not what the port contract generates: run 'pluecker contract --write rtl' (make contract)";
}

}  // namespace
}  // namespace pluecker
