// SPDX-License-Identifier: MIT
// The port contract (contract.hpp): the derived constants at the edges of
// every rule, the parameter checks, the port encoding, the class table, and
// that the committed generated files (rtl/pluecker_contract_pkg.sv,
// rtl/pluecker_contract.json) are what this build generates.
#include "pluecker/app/names.hpp"  // parse_mul_style
#include "pluecker/axis_contract.hpp"
#include "pluecker/contract.hpp"
#include "pluecker/fixed.hpp"
#include "pluecker/rng.hpp"

#include <gtest/gtest.h>

#include <fstream>
#include <iterator>
#include <sstream>
#include <string>

#ifndef PLUECKER_RTL_DIR
#error "PLUECKER_RTL_DIR must name the rtl/ directory (model/CMakeLists.txt)"
#endif

namespace pluecker {
namespace {

PortContract contract(int c, int d, MulStyle s = MulStyle::Auto, int pipeline = 0) {
    RtlConfig cfg;
    cfg.coord_bits = c;
    cfg.dir_bits = d;
    cfg.mul_style = s;
    cfg.pipeline = pipeline;
    return PortContract(cfg);
}

TEST(Contract, LimitsAreTheFormatLimits) {
    EXPECT_EQ(FixedFormat::kMinBits, ContractLimits::kMinBits);
    EXPECT_EQ(FixedFormat::kMaxBits, ContractLimits::kMaxBits);
    EXPECT_EQ(FixedFormat::kDefaultCoordBits, ContractDefaults::kCoordBits);
    EXPECT_EQ(FixedFormat::kDefaultDirBits, ContractDefaults::kDirBits);
    EXPECT_EQ(ContractLimits::kMinBits, 6);
    EXPECT_EQ(ContractLimits::kMaxBits, 24);
}

// The rules of rtl/pluecker_intersector.sv at the edges of every threshold.
TEST(Contract, LatencyAndFifoDepthPerClass) {
    struct Case {
        int c, d, pipeline;
        int mul_add, latency, fifo_depth, dsp;
    };
    const Case cases[] = {
        {6, 6, 0, 0, 6, 8, 0},      {9, 9, 0, 0, 6, 8, 0},      {10, 9, 0, 0, 6, 8, 12},
        {16, 16, 0, 0, 6, 8, 12},   {17, 17, 0, 0, 6, 8, 12},   {18, 17, 0, 1, 7, 16, 24},
        {17, 18, 0, 1, 7, 16, 24},  {6, 24, 0, 1, 7, 16, 24},   {24, 6, 0, 1, 7, 16, 24},
        {18, 18, 0, 2, 8, 16, 48},  {24, 24, 0, 2, 8, 16, 48},  {6, 6, 1, 0, 7, 16, 0},
        {16, 16, 1, 0, 7, 16, 12},  {18, 6, 1, 1, 8, 16, 24},   {24, 24, 1, 2, 9, 16, 48},
    };
    for (const Case& k : cases) {
        SCOPED_TRACE(std::to_string(k.c) + "/" + std::to_string(k.d) + " PIPELINE " + std::to_string(k.pipeline));
        const PortContract pc = contract(k.c, k.d, MulStyle::Auto, k.pipeline);
        EXPECT_EQ(pc.mul_add(), k.mul_add);
        EXPECT_EQ(pc.s2x_stages(), k.pipeline + k.mul_add);
        EXPECT_EQ(pc.latency(), k.latency);
        EXPECT_EQ(pc.fifo_depth(), k.fifo_depth);
        EXPECT_EQ(pc.dsp_blocks(), k.dsp);
        EXPECT_EQ(pc.fabric_multipliers(), k.dsp == 0);
        EXPECT_EQ(pc.mul_a_bits(), k.c + 1);
        EXPECT_EQ(pc.mul_b_bits(), k.d + 1);
    }
}

TEST(Contract, MultiplierStyles) {
    EXPECT_TRUE(contract(9, 9).fabric_multipliers());
    EXPECT_FALSE(contract(10, 9).fabric_multipliers());
    EXPECT_FALSE(contract(9, 10).fabric_multipliers());
    EXPECT_FALSE(contract(6, 6, MulStyle::Dsp).fabric_multipliers());
    EXPECT_EQ(contract(6, 6, MulStyle::Dsp).dsp_blocks(), 12);
    // Paired products (rtl/pluecker_mul_pair.sv): DSP, PIPELINE 2 and
    // C + 2 D <= 18 only, i.e. 6/6; same latency as unpaired.
    EXPECT_TRUE(contract(6, 6, MulStyle::Dsp, 2).paired_products());
    EXPECT_EQ(contract(6, 6, MulStyle::Dsp, 2).dsp_blocks(), 6);
    EXPECT_EQ(contract(6, 6, MulStyle::Dsp, 2).latency(), contract(7, 7, MulStyle::Dsp, 2).latency());
    EXPECT_FALSE(contract(6, 6, MulStyle::Dsp, 1).paired_products());
    EXPECT_FALSE(contract(6, 6, MulStyle::Auto, 2).paired_products());  // fabric
    EXPECT_FALSE(contract(6, 6, MulStyle::Lut, 2).paired_products());
    EXPECT_EQ(contract(7, 6, MulStyle::Dsp, 2).dsp_blocks(), 12);
    EXPECT_EQ(contract(6, 7, MulStyle::Dsp, 2).dsp_blocks(), 12);
    EXPECT_TRUE(contract(17, 17, MulStyle::Lut).fabric_multipliers());
    EXPECT_EQ(contract(17, 17, MulStyle::Lut).latency(), 6);
    // The style never changes the latency.
    for (MulStyle s : {MulStyle::Auto, MulStyle::Dsp, MulStyle::Lut})
        for (int p = 0; p <= 1; ++p) EXPECT_EQ(contract(8, 12, s, p).latency(), 6 + p);
    // Block-RAM tables (rtl/pluecker_mul_rom.sv): 6/6 with PIPELINE 2 only,
    // twelve DP16KD and no MULT18X18D, the latency of the other styles.
    const PortContract rom = contract(6, 6, MulStyle::Rom, 2);
    EXPECT_TRUE(rom.rom_multipliers());
    EXPECT_FALSE(rom.fabric_multipliers());
    EXPECT_FALSE(rom.paired_products());
    EXPECT_EQ(rom.dsp_blocks(), 0);
    EXPECT_EQ(rom.rom_blocks(), 12);
    EXPECT_EQ(rom.latency(), contract(6, 6, MulStyle::Dsp, 2).latency());
    EXPECT_EQ(contract(6, 6, MulStyle::Dsp, 2).rom_blocks(), 0);
    EXPECT_EQ(contract(6, 6, MulStyle::Lut, 2).rom_blocks(), 0);
    EXPECT_EQ(parse_mul_style("lut"), MulStyle::Lut);
    EXPECT_EQ(parse_mul_style("rom"), MulStyle::Rom);
    EXPECT_STREQ(mul_style_name(MulStyle::Rom), "rom");
    EXPECT_STREQ(mul_style_name(MulStyle::Dsp), "dsp");
    EXPECT_THROW(parse_mul_style("fast"), InputError);
}

TEST(Contract, RefusesWhatTheRtlRefuses) {
    auto refuses = [](RtlConfig c, const std::string& part) {
        try {
            validate_rtl_config(c);
        } catch (const InputError& e) {
            EXPECT_NE(std::string(e.what()).find(part), std::string::npos) << e.what();
            EXPECT_THROW(PortContract{c}, InputError);
            return;
        }
        ADD_FAILURE() << "accepted, expected a message with '" << part << "'";
    };
    RtlConfig c;
    c.coord_bits = 5;
    refuses(c, "COORD_BITS = 5 is outside the supported 6..24");
    c = RtlConfig{};
    c.dir_bits = 25;
    refuses(c, "DIR_BITS = 25");
    c = RtlConfig{};
    c.tag_bits = 0;
    refuses(c, "TAG_BITS = 0");
    c = RtlConfig{};
    c.pipeline = 3;
    refuses(c, "PIPELINE = 3 is outside 0..2");
    c = RtlConfig{};
    c.mul_style = MulStyle::Lut;
    c.coord_bits = 18;
    refuses(c, "MUL_STYLE lut supports COORD_BITS and DIR_BITS up to 17");
    c.coord_bits = 17;
    c.dir_bits = 18;
    refuses(c, "MUL_STYLE lut");
    c = RtlConfig{};
    c.mul_style = MulStyle::Rom;
    c.coord_bits = c.dir_bits = 6;
    c.pipeline = 1;
    refuses(c, "MUL_STYLE rom needs PIPELINE = 2 (PIPELINE = 1)");
    c.pipeline = 2;
    EXPECT_NO_THROW(validate_rtl_config(c));
    c.dir_bits = 7;
    refuses(c, "MUL_STYLE rom needs COORD_BITS + 1 + ceil(DIR_BITS / 2) <= 10");
    c.dir_bits = 6;
    c.coord_bits = 7;
    refuses(c, "(COORD_BITS = 7, DIR_BITS = 6)");
    EXPECT_NO_THROW(validate_rtl_config(RtlConfig{}));
}

TEST(Contract, Ports) {
    RtlConfig cfg;
    cfg.coord_bits = 10;
    cfg.dir_bits = 12;
    cfg.tag_bits = 5;
    const PortContract pc(cfg);
    EXPECT_EQ(pc.ports().size(), 17u);
    EXPECT_EQ(pc.port("ray_org_i").width(), 30);
    EXPECT_EQ(pc.port("ray_org_i").field_lsb(1), 10);
    EXPECT_TRUE(pc.port("box_max_i").is_signed);
    EXPECT_EQ(pc.port("ray_dir_i").width(), 36);
    EXPECT_FALSE(pc.port("ray_dir_i").is_signed);
    EXPECT_EQ(pc.port("in_tag_i").width(), 5);
    EXPECT_EQ(pc.port("out_tag_o").dir, PortDir::Out);
    EXPECT_EQ(pc.port("ray_class_i").width(), 3);
    EXPECT_THROW(pc.port("ray_org"), InputError);
    const FixedFormat f = pc.format();
    EXPECT_EQ(f.coord_bits, 10);
    EXPECT_EQ(f.dir_bits, 12);
    EXPECT_EQ(f.mode, FixedMode::Conservative);
}

FixedFormat fmt(int c, int d) {
    FixedFormat f;
    f.coord_bits = c;
    f.dir_bits = d;
    return f;
}

// x in the low field, two's complement coordinates, fields across words.
TEST(Contract, PackPlacesFields) {
    FixedRay r;
    r.cls = 5;
    r.org = {1, -1, 2};
    r.dir = {32, 0, 63};
    r.end = {-32, 31, 0};
    r.has_end = true;
    FixedBox b;
    b.lo = {-2, -3, -4};
    b.hi = {3, 4, 5};
    const QueryPorts p = pack_query(r, b, fmt(6, 6));
    EXPECT_EQ(p.ray_class, 5u);
    EXPECT_EQ(p.ray_org[0], 1u | (63u << 6) | (2u << 12));
    EXPECT_EQ(p.ray_dir[0], 32u | (0u << 6) | (63u << 12));
    EXPECT_EQ(p.ray_end[0], 32u | (31u << 6));
    EXPECT_EQ(p.ray_end_valid, 1u);
    EXPECT_EQ(p.ray_org[1], 0u);
    // 24-bit fields: y straddles words 0 and 1, z is bits 48..71.
    FixedRay w;
    w.org = {-1, (std::int64_t{1} << 23) - 1, -(std::int64_t{1} << 23)};
    w.dir = {(std::int64_t{1} << 24) - 1, 1, 0};
    const QueryPorts q = pack_query(w, FixedBox{}, fmt(24, 24));
    EXPECT_EQ(q.ray_org[0], 0x00ffffffu | (0xffu << 24));
    EXPECT_EQ(q.ray_org[1], 0x7fffu | (0x0000u << 16));
    EXPECT_EQ(q.ray_org[2], 0x80u);
    EXPECT_EQ(q.ray_dir[0], 0x01ffffffu);
    EXPECT_EQ(q.ray_dir[1], 0u);
    EXPECT_EQ(q.ray_end_valid, 0u);
}

TEST(Contract, PackUnpackRoundTrip) {
    Rng g(7);
    for (int c : {6, 11, 16, 21, 24})
        for (int d : {6, 13, 24}) {
            const FixedFormat f = fmt(c, d);
            for (int n = 0; n < 200; ++n) {
                FixedRay r;
                FixedBox b;
                auto coord = [&] { return f.coord_min() + static_cast<std::int64_t>(g.next() % (std::uint64_t{1} << c)); };
                r.cls = static_cast<RayClass>(g.next() % 8);
                r.has_end = g.next() % 2;
                for (std::size_t a = 0; a < 3; ++a) {
                    r.org[a] = coord();
                    r.end[a] = coord();
                    b.lo[a] = coord();
                    b.hi[a] = coord();
                    r.dir[a] = static_cast<std::int64_t>(g.next() % (std::uint64_t{1} << d));
                }
                FixedRay r2;
                FixedBox b2;
                unpack_query(pack_query(r, b, f), f, r2, b2);
                ASSERT_EQ(r2.cls, r.cls);
                ASSERT_EQ(r2.org, r.org);
                ASSERT_EQ(r2.dir, r.dir);
                ASSERT_EQ(r2.end, r.end);
                ASSERT_EQ(r2.has_end, r.has_end);
                ASSERT_EQ(b2.lo, b.lo);
                ASSERT_EQ(b2.hi, b.hi);
            }
        }
}

TEST(Contract, PackRefusesOperandsThatDoNotFit) {
    const FixedFormat f = fmt(6, 6);
    auto refuses = [&](const FixedRay& r, const FixedBox& b, const std::string& part) {
        try {
            pack_query(r, b, f);
        } catch (const InputError& e) {
            EXPECT_NE(std::string(e.what()).find(part), std::string::npos) << e.what();
            return;
        }
        ADD_FAILURE() << "packed, expected '" << part << "'";
    };
    FixedRay r;
    FixedBox b;
    r.org[0] = 32;
    refuses(r, b, "ray origin x = 32 does not fit COORD_BITS = 6 (range -32..31)");
    r = FixedRay{};
    r.end[2] = -33;
    refuses(r, b, "ray end z = -33");
    r = FixedRay{};
    r.dir[1] = 64;
    refuses(r, b, "ray direction y = 64 does not fit DIR_BITS = 6 (range 0..63)");
    r = FixedRay{};
    r.dir[1] = -1;
    refuses(r, b, "ray direction y = -1");
    r = FixedRay{};
    r.cls = 8;
    refuses(r, b, "ray class 8 is outside 0..7");
    r = FixedRay{};
    b.hi[1] = 100;
    refuses(r, b, "box hi y = 100");
    EXPECT_THROW(pack_query(FixedRay{}, FixedBox{}, fmt(5, 6)), InputError);
}

// The classes partition every configuration, each row equal to the contract.
TEST(Contract, ClassesPartitionEveryConfiguration) {
    const std::vector<ContractClass> classes = contract_classes();
    ASSERT_FALSE(classes.empty());
    std::size_t valid = 0;
    for (int c = ContractLimits::kMinBits; c <= ContractLimits::kMaxBits; ++c)
        for (int d = ContractLimits::kMinBits; d <= ContractLimits::kMaxBits; ++d)
            for (MulStyle s : {MulStyle::Auto, MulStyle::Dsp, MulStyle::Lut, MulStyle::Rom})
                for (int p = 0; p <= ContractLimits::kMaxPipeline; ++p) {
                    SCOPED_TRACE(std::to_string(c) + "/" + std::to_string(d) + " " + mul_style_name(s) + " " +
                                 std::to_string(p));
                    RtlConfig cfg;
                    cfg.coord_bits = c;
                    cfg.dir_bits = d;
                    cfg.mul_style = s;
                    cfg.pipeline = p;
                    int hits = 0;
                    const ContractClass* in = nullptr;
                    for (const ContractClass& k : classes)
                        if (c >= k.coord_lo && c <= k.coord_hi && d >= k.dir_lo && d <= k.dir_hi &&
                            k.mul_style == s && k.pipeline == p) {
                            ++hits;
                            in = &k;
                        }
                    bool ok = true;
                    try {
                        validate_rtl_config(cfg);
                    } catch (const InputError&) {
                        ok = false;
                    }
                    if (!ok) {
                        EXPECT_EQ(hits, 0);
                        continue;
                    }
                    ++valid;
                    ASSERT_EQ(hits, 1);
                    const PortContract pc(cfg);
                    EXPECT_EQ(in->fabric, pc.fabric_multipliers());
                    EXPECT_EQ(in->mul_add, pc.mul_add());
                    EXPECT_EQ(in->s2x_stages, pc.s2x_stages());
                    EXPECT_EQ(in->latency, pc.latency());
                    EXPECT_EQ(in->fifo_depth, pc.fifo_depth());
                    EXPECT_EQ(in->dsp_blocks, pc.dsp_blocks());
                    EXPECT_EQ(in->rom, pc.rom_multipliers());
                    EXPECT_EQ(in->rom_blocks, pc.rom_blocks());
                }
    // auto and dsp: every width pair; lut: both widths up to 17; three
    // PIPELINE values; rom: 6/6 at PIPELINE 2.
    EXPECT_EQ(valid, std::size_t{3} * (19 * 19 * 2 + 12 * 12) + 1);
    // Widths split at 7 (paired products and tables at 6/6), 10 (auto's
    // fabric threshold) and 18 (DSP operand split): auto and dsp 4 x 4
    // runs, lut 3 x 3, for each PIPELINE; rom one class.
    EXPECT_EQ(classes.size(), std::size_t{3} * (16 + 16 + 9) + 1);
}

// The AXI4-Stream wrapper's tdata: the payload ports back to back from bit
// 0, in port-list order, padded to whole bytes.
TEST(Contract, AxisTdataFields) {
    for (int c = ContractLimits::kMinBits; c <= ContractLimits::kMaxBits; ++c)
        for (int d = ContractLimits::kMinBits; d <= ContractLimits::kMaxBits; ++d) {
            SCOPED_TRACE(std::to_string(c) + "/" + std::to_string(d));
            const PortContract pc = contract(c, d);
            const auto f = axis_tdata_fields(pc);
            const char* order[] = {"ray_class_i", "ray_org_i", "ray_dir_i", "ray_end_i",
                                   "ray_end_valid_i", "box_min_i", "box_max_i"};
            ASSERT_EQ(f.size(), std::size(order));
            int lsb = 0;
            for (std::size_t k = 0; k < f.size(); ++k) {
                EXPECT_EQ(f[k].port, order[k]);
                EXPECT_EQ(f[k].lsb, lsb);
                EXPECT_EQ(f[k].width, pc.port(f[k].port).width());
                lsb += f[k].width;
            }
            EXPECT_EQ(axis_query_bits(pc), 4 + 12 * c + 3 * d);
            EXPECT_EQ(axis_tdata_bits(pc) % 8, 0);
            EXPECT_GE(axis_tdata_bits(pc), axis_query_bits(pc));
            EXPECT_LT(axis_tdata_bits(pc) - axis_query_bits(pc), 8);
        }
    // The terms behind the generated package's functions give the same table.
    const auto terms = axis_tdata_terms();
    for (int c = ContractLimits::kMinBits; c <= ContractLimits::kMaxBits; ++c)
        for (int d = ContractLimits::kMinBits; d <= ContractLimits::kMaxBits; ++d) {
            const auto f = axis_tdata_fields(contract(c, d));
            ASSERT_EQ(terms.size(), f.size());
            for (std::size_t k = 0; k < f.size(); ++k) {
                EXPECT_EQ(terms[k].port, f[k].port);
                EXPECT_EQ(terms[k].lsb.at(c, d), f[k].lsb) << c << "/" << d << " " << f[k].port;
                EXPECT_EQ(terms[k].width.at(c, d), f[k].width) << c << "/" << d << " " << f[k].port;
            }
        }
    EXPECT_NE(contract_sv_package().find("      2: axis_field_lsb = 3 + 3 * c;  // ray_dir_i"), std::string::npos);
    EXPECT_EQ(axis_tdata_bits(contract(16, 16)), 248);  // 244 bits of fields
    EXPECT_EQ(axis_tdata_bits(contract(6, 6)), 96);     // 94
    EXPECT_EQ(axis_tdata_bits(contract(24, 24)), 368);  // 364
}

std::string read_file(const std::string& path) {
    std::ifstream in(path, std::ios::binary);
    EXPECT_TRUE(in) << "cannot read " << path;
    std::ostringstream s;
    s << in.rdbuf();
    return s.str();
}

TEST(Contract, GeneratedFilesAreCurrent) {
    const std::string dir = PLUECKER_RTL_DIR;
    EXPECT_EQ(read_file(dir + "/" + kContractSvFile), contract_sv_package())
        << dir << "/" << kContractSvFile
        << " is not what the port contract generates: run 'pluecker contract --write rtl' (make contract)";
    EXPECT_EQ(read_file(dir + "/" + kContractJsonFile), contract_json())
        << dir << "/" << kContractJsonFile
        << " is not what the port contract generates: run 'pluecker contract --write rtl' (make contract)";
}

}  // namespace
}  // namespace pluecker
