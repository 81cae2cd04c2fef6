// SPDX-License-Identifier: MIT
// The port contract of the local unit (local_contract.hpp): the derived
// constants at the edges of every rule, the parameter checks, the port
// encoding of a (LocalRay, LocalFrame, LocalBox[CHILDREN]) query, the class
// table, and that the committed generated files
// (rtl/pluecker_local_contract_pkg.sv, rtl/pluecker_local_contract.json) are
// what this build generates.
#include "pluecker/local_contract.hpp"
#include "pluecker/querygen.hpp"
#include "pluecker/rng.hpp"

#include <gtest/gtest.h>

#include <fstream>
#include <sstream>
#include <string>

#ifndef PLUECKER_RTL_DIR
#error "PLUECKER_RTL_DIR must name the rtl/ directory (model/CMakeLists.txt)"
#endif

namespace pluecker {
namespace {

using i64 = std::int64_t;

LocalRtlConfig config(int k, int d, int g, MulStyle s = MulStyle::Auto, int children = 1) {
    LocalRtlConfig c;
    c.box_bits = k;
    c.dir_bits = d;
    c.grid_bits = g;
    c.mul_style = s;
    c.children = children;
    return c;
}

TEST(LocalContract, LimitsAreTheFormatLimits) {
    EXPECT_EQ(LocalContractLimits::kMinBoxBits, LocalFormat::kMinBoxBits);
    EXPECT_EQ(LocalContractLimits::kMaxBoxBits, LocalFormat::kMaxBoxBits);
    EXPECT_EQ(LocalContractLimits::kMinDirBits, LocalFormat::kMinDirBits);
    EXPECT_EQ(LocalContractLimits::kMaxDirBits, LocalFormat::kMaxDirBits);
    EXPECT_LE(LocalContractLimits::kMaxGridBits, LocalFormat::kMaxGridBits);
    const LocalFormat def;
    EXPECT_EQ(def.box_bits, LocalContractDefaults::kBoxBits);
    EXPECT_EQ(def.dir_bits, LocalContractDefaults::kDirBits);
    EXPECT_EQ(def.grid_bits, LocalContractDefaults::kGridBits);
}

// The rules of rtl/pluecker_local_intersector.sv at the edges of every threshold.
TEST(LocalContract, LatencyFifoAndDspPerRule) {
    struct Case {
        int k, d, g;
        MulStyle s;
        int children;
        int frame_add, child_add, latency, fifo, dsp;
    };
    const Case cases[] = {
        {4, 4, 6, MulStyle::Auto, 1, 0, 0, 14, 16, 6},       {8, 11, 15, MulStyle::Auto, 1, 0, 0, 14, 16, 6},
        {8, 11, 16, MulStyle::Auto, 2, 1, 0, 15, 32, 12},    {8, 11, 17, MulStyle::Auto, 1, 1, 0, 15, 32, 12},
        {8, 11, 18, MulStyle::Auto, 1, 2, 0, 16, 32, 24},    {8, 11, 32, MulStyle::Auto, 2, 2, 0, 16, 32, 24},
        {16, 24, 32, MulStyle::Auto, 2, 2, 0, 16, 32, 24},   {8, 11, 32, MulStyle::Dsp, 1, 2, 0, 16, 32, 36},
        {8, 11, 32, MulStyle::Dsp, 2, 2, 0, 16, 32, 48},     {8, 17, 32, MulStyle::Dsp, 2, 2, 0, 16, 32, 48},
        {8, 18, 32, MulStyle::Dsp, 2, 2, 1, 17, 32, 72},     {8, 18, 12, MulStyle::Dsp, 1, 0, 1, 15, 32, 30},
        {8, 24, 32, MulStyle::Lut, 2, 0, 0, 14, 16, 0},      {4, 4, 6, MulStyle::Lut, 1, 0, 0, 14, 16, 0},
    };
    for (const Case& k : cases) {
        SCOPED_TRACE(std::to_string(k.k) + "/" + std::to_string(k.d) + "/" + std::to_string(k.g) + " " +
                     mul_style_name(k.s) + " x" + std::to_string(k.children));
        const LocalPortContract pc(config(k.k, k.d, k.g, k.s, k.children));
        EXPECT_EQ(pc.frame_mul_add(), k.frame_add);
        EXPECT_EQ(pc.child_mul_add(), k.child_add);
        EXPECT_EQ(pc.frame_latency(), 9 + k.frame_add);
        EXPECT_EQ(pc.child_latency(), 4 + k.child_add);
        EXPECT_EQ(pc.latency(), k.latency);
        EXPECT_EQ(pc.fifo_depth(), k.fifo);
        EXPECT_EQ(pc.dsp_blocks(), k.dsp);
        EXPECT_EQ(pc.frame_fabric(), k.s == MulStyle::Lut);
        EXPECT_EQ(pc.child_fabric(), k.s != MulStyle::Dsp);
    }
}

TEST(LocalContract, ExpBits) {
    EXPECT_EQ(local_exp_bits(32, 8), 5);   // exponents 0..25
    EXPECT_EQ(local_exp_bits(6, 4), 2);    // 0..3
    EXPECT_EQ(local_exp_bits(32, 4), 5);   // 0..29
    EXPECT_EQ(local_exp_bits(18, 16), 2);  // 0..3
    EXPECT_EQ(local_exp_bits(17, 8), 4);   // 0..10
    for (int k = 4; k <= 16; ++k)
        for (int g = k + 2; g <= 32; ++g) {
            const int e = local_exp_bits(g, k);
            EXPECT_GE(1 << e, g - k + 2);
            EXPECT_LT(1 << (e - 1), g - k + 2);
        }
}

TEST(LocalContract, RefusesWhatTheRtlRefuses) {
    auto refuses = [](LocalRtlConfig c, const std::string& part) {
        try {
            validate_local_rtl_config(c);
        } catch (const InputError& e) {
            EXPECT_NE(std::string(e.what()).find(part), std::string::npos) << e.what();
            EXPECT_THROW(LocalPortContract{c}, InputError);
            return;
        }
        ADD_FAILURE() << "accepted, expected a message with '" << part << "'";
    };
    refuses(config(3, 11, 32), "BOX_BITS = 3 is outside the supported 4..16");
    refuses(config(17, 11, 32), "BOX_BITS = 17");
    refuses(config(8, 3, 32), "DIR_BITS = 3");
    refuses(config(8, 25, 32), "DIR_BITS = 25");
    refuses(config(8, 11, 9), "GRID_BITS = 9 is outside the supported 10..32");
    refuses(config(8, 11, 33), "GRID_BITS = 33");
    refuses(config(8, 11, 32, MulStyle::Auto, 3), "CHILDREN = 3");
    refuses(config(8, 11, 32, MulStyle::Auto, 0), "CHILDREN = 0");
    LocalRtlConfig c;
    c.tag_bits = 0;
    refuses(c, "TAG_BITS = 0");
    EXPECT_NO_THROW(validate_local_rtl_config(LocalRtlConfig{}));
    EXPECT_NO_THROW(validate_local_rtl_config(config(16, 24, 18, MulStyle::Lut, 2)));
}

TEST(LocalContract, Ports) {
    LocalRtlConfig cfg = config(8, 11, 32, MulStyle::Auto, 2);
    cfg.tag_bits = 5;
    const LocalPortContract pc(cfg);
    EXPECT_EQ(pc.ports().size(), 18u);
    EXPECT_EQ(pc.port("ray_org_i").width(), 96);
    EXPECT_TRUE(pc.port("ray_org_i").is_signed);
    EXPECT_FALSE(pc.port("ray_dir_i").is_signed);
    EXPECT_TRUE(pc.port("frame_org_i").is_signed);
    EXPECT_EQ(pc.port("frame_exp_i").width(), 15);
    EXPECT_EQ(pc.port("box_min_i").width(), 48);
    EXPECT_EQ(pc.port("box_min_i").fields, 6);
    EXPECT_EQ(pc.port("box_max_i").field_lsb(4), 32);  // child 1, y
    EXPECT_EQ(pc.port("out_hit_o").width(), 2);
    EXPECT_EQ(pc.port("in_tag_i").width(), 5);
    EXPECT_THROW(pc.port("box_lo_i"), InputError);
    const LocalFormat f = pc.format();
    EXPECT_EQ(f.box_bits, 8);
    EXPECT_EQ(f.dir_bits, 11);
    EXPECT_EQ(f.grid_bits, 32);
    EXPECT_EQ(f.mode, FixedMode::Conservative);
}

// A ray as local_setup_ray makes it and boxes in the frame.
struct Operands {
    LocalRay ray;
    LocalFrame frame;
    std::vector<LocalBox> boxes;
};

Operands random_operands(Rng& g, const LocalPortContract& c) {
    const LocalFormat f = c.format();
    auto grid = [&] { return f.grid_min() + static_cast<i64>(g.next() % (std::uint64_t{1} << f.grid_bits)); };
    const i64 top = i64{1} << (f.grid_bits - 1);
    Operands o;
    o.ray.cls = static_cast<RayClass>(g.next() % 8);
    o.ray.has_end = g.next() % 2;
    for (std::size_t a = 0; a < 3; ++a) {
        o.ray.org[a] = grid();
        o.ray.end[a] = grid();
        o.ray.dir_g[a] = static_cast<i64>(g.next() % static_cast<std::uint64_t>(top + 1));
        o.frame.origin[a] = grid();
        o.frame.exp[a] = static_cast<int>(g.next() % static_cast<std::uint64_t>(f.max_exp() + 1));
    }
    o.ray.dir_g[g.next() % 3] = top;
    o.boxes.resize(static_cast<std::size_t>(c.config().children));
    for (LocalBox& b : o.boxes)
        for (std::size_t a = 0; a < 3; ++a) {
            b.lo[a] = static_cast<i64>(g.next() % static_cast<std::uint64_t>(f.box_max() + 1));
            b.hi[a] = static_cast<i64>(g.next() % static_cast<std::uint64_t>(f.box_max() + 1));
        }
    return o;
}

TEST(LocalContract, PackPlacesFields) {
    const LocalPortContract pc(config(4, 4, 6, MulStyle::Auto, 2));  // EXP_BITS 2
    LocalRay r;
    r.cls = 6;
    r.org = {1, -1, -32};
    r.dir_g = {32, 0, 7};
    r.end = {31, 0, -2};
    r.has_end = true;
    LocalFrame fr;
    fr.origin = {-1, 2, 0};
    fr.exp = {3, 0, 1};
    const std::vector<LocalBox> boxes = {LocalBox{{1, 2, 3}, {15, 14, 13}}, LocalBox{{0, 5, 0}, {9, 5, 15}}};
    const LocalQueryPorts p = pack_local_query(r, fr, boxes, pc);
    EXPECT_EQ(p.ray_class, 6u);
    EXPECT_EQ(p.ray_org[0], 1u | (63u << 6) | (32u << 12));
    EXPECT_EQ(p.ray_dir[0], 32u | (7u << 12));
    EXPECT_EQ(p.ray_end[0], 31u | (62u << 12));
    EXPECT_EQ(p.ray_end_valid, 1u);
    EXPECT_EQ(p.frame_org[0], 63u | (2u << 6));
    EXPECT_EQ(p.frame_exp, 3u | (0u << 2) | (1u << 4));
    EXPECT_EQ(p.box_min[0], 1u | (2u << 4) | (3u << 8) | (0u << 12) | (5u << 16) | (0u << 20));
    EXPECT_EQ(p.box_max[0], 15u | (14u << 4) | (13u << 8) | (9u << 12) | (5u << 16) | (15u << 20));
    // 32-bit fields: one word each.
    const LocalPortContract wide(config(16, 24, 32, MulStyle::Auto, 2));
    LocalRay w;
    w.org = {-1, 5, -(i64{1} << 31)};
    w.dir_g = {i64{1} << 31, 3, 0};
    const std::vector<LocalBox> wb = {LocalBox{{0xffff, 0, 1}, {0, 0, 0}}, LocalBox{{0, 0, 0}, {0, 0, 0xabcd}}};
    const LocalQueryPorts q = pack_local_query(w, LocalFrame{}, wb, wide);
    EXPECT_EQ(q.ray_org[0], 0xffffffffu);
    EXPECT_EQ(q.ray_org[1], 5u);
    EXPECT_EQ(q.ray_org[2], 0x80000000u);
    EXPECT_EQ(q.ray_dir[0], 0x80000000u);
    EXPECT_EQ(q.box_min[0], 0xffffu);
    EXPECT_EQ(q.box_min[1], 1u);
    EXPECT_EQ(q.box_max[2], 0xabcd0000u);
}

TEST(LocalContract, PackUnpackRoundTrip) {
    Rng g(11);
    for (const LocalRtlConfig& cfg : {config(4, 4, 6), config(8, 11, 32, MulStyle::Auto, 2), config(12, 15, 21),
                                      config(16, 24, 32, MulStyle::Dsp, 2), config(16, 19, 18, MulStyle::Lut, 1)}) {
        const LocalPortContract pc(cfg);
        for (int n = 0; n < 300; ++n) {
            const Operands o = random_operands(g, pc);
            LocalRay r2;
            LocalFrame f2;
            std::vector<LocalBox> b2;
            unpack_local_query(pack_local_query(o.ray, o.frame, o.boxes, pc), pc, r2, f2, b2);
            ASSERT_EQ(r2.cls, o.ray.cls);
            ASSERT_EQ(r2.org, o.ray.org);
            ASSERT_EQ(r2.dir_g, o.ray.dir_g);
            ASSERT_EQ(r2.end, o.ray.end);
            ASSERT_EQ(r2.has_end, o.ray.has_end);
            ASSERT_EQ(f2, o.frame);
            ASSERT_EQ(b2, o.boxes);
        }
    }
}

// Queries from the model's own set-up are inside the contract.
TEST(LocalContract, SetUpQueriesFitTheContract) {
    for (const LocalRtlConfig& cfg : {config(4, 7, 6), config(8, 11, 32), config(16, 19, 32)}) {
        const LocalPortContract pc(cfg);
        const LocalFormat f = pc.format();
        std::size_t packed = 0;
        for (const Query& q : extreme_queries(3, 400)) {
            LocalFrame fr;
            LocalBox b;
            try {
                fr = local_frame_for(q.box, f);
                b = local_quantize_box(q.box, fr, f);
            } catch (const InputError&) {
                continue;  // a box outside the range
            }
            const std::optional<LocalRay> r = local_setup_ray(q.ray, f);
            if (!r) continue;
            EXPECT_NO_THROW(pack_local_query(*r, fr, std::vector<LocalBox>{b}, pc));
            ++packed;
        }
        EXPECT_GT(packed, 300u);
    }
}

TEST(LocalContract, PackRefusesOperandsOutsideTheContract) {
    const LocalPortContract pc(config(4, 4, 6));
    auto refuses = [&](const LocalRay& r, const LocalFrame& fr, const std::vector<LocalBox>& b,
                       const std::string& part) {
        try {
            pack_local_query(r, fr, b, pc);
        } catch (const InputError& e) {
            EXPECT_NE(std::string(e.what()).find(part), std::string::npos) << e.what();
            return;
        }
        ADD_FAILURE() << "packed, expected '" << part << "'";
    };
    LocalRay ok;
    ok.dir_g = {32, 0, 0};
    const std::vector<LocalBox> one(1);
    LocalRay r = ok;
    r.org[0] = 32;
    refuses(r, LocalFrame{}, one, "ray origin x = 32 does not fit GRID_BITS = 6 (range -32..31)");
    r = ok;
    r.end[2] = -33;
    refuses(r, LocalFrame{}, one, "ray end z = -33");
    r = ok;
    r.dir_g[1] = 33;
    refuses(r, LocalFrame{}, one, "ray direction y = 33 is outside 0..32");
    r = ok;
    r.dir_g = {31, 5, 0};
    refuses(r, LocalFrame{}, one, "the largest component is 31, not 2^(GRID_BITS - 1) = 32");
    r = ok;
    r.cls = 8;
    refuses(r, LocalFrame{}, one, "ray class 8 is outside 0..7");
    LocalFrame fr;
    fr.exp[1] = 4;
    refuses(ok, fr, one, "frame exponent y = 4 is outside 0..3");
    fr = LocalFrame{};
    fr.origin[2] = 40;
    refuses(ok, fr, one, "frame origin z = 40");
    std::vector<LocalBox> b(1);
    b[0].hi[1] = 16;
    refuses(ok, LocalFrame{}, b, "box 0 y offset 16 is outside 0..15");
    refuses(ok, LocalFrame{}, std::vector<LocalBox>(2), "2 boxes for CHILDREN = 1");
    EXPECT_NO_THROW(pack_local_query(ok, LocalFrame{}, one, pc));
}

// The classes partition every configuration, each row equal to the contract.
TEST(LocalContract, ClassesPartitionEveryConfiguration) {
    using L = LocalContractLimits;
    const std::vector<LocalContractClass> classes = local_contract_classes();
    ASSERT_FALSE(classes.empty());
    std::size_t valid = 0;
    for (int k = L::kMinBoxBits; k <= L::kMaxBoxBits; ++k)
        for (int d = L::kMinDirBits; d <= L::kMaxDirBits; ++d)
            for (int g = k + L::kGridMargin; g <= L::kMaxGridBits; ++g)
                for (MulStyle s : {MulStyle::Auto, MulStyle::Dsp, MulStyle::Lut})
                    for (int ch = 1; ch <= L::kMaxChildren; ++ch) {
                        const LocalRtlConfig cfg = config(k, d, g, s, ch);
                        int hits = 0;
                        const LocalContractClass* in = nullptr;
                        for (const LocalContractClass& c : classes)
                            if (d >= c.dir_lo && d <= c.dir_hi && g >= c.grid_lo && g <= c.grid_hi &&
                                c.mul_style == s) {
                                ++hits;
                                in = &c;
                            }
                        ++valid;
                        ASSERT_EQ(hits, 1) << k << "/" << d << "/" << g;
                        const LocalPortContract pc(cfg);
                        ASSERT_EQ(in->frame_fabric, pc.frame_fabric());
                        ASSERT_EQ(in->child_fabric, pc.child_fabric());
                        ASSERT_EQ(in->frame_mul_add, pc.frame_mul_add());
                        ASSERT_EQ(in->child_mul_add, pc.child_mul_add());
                        ASSERT_EQ(in->latency, pc.latency());
                        ASSERT_EQ(in->fifo_depth, pc.fifo_depth());
                        ASSERT_EQ(in->frame_dsp_blocks + ch * in->child_dsp_blocks, pc.dsp_blocks());
                    }
    EXPECT_GT(valid, 0u);
    // DIR_BITS split at 18 (the DSP operand split), GRID_BITS at 16 and 18; three styles.
    EXPECT_EQ(classes.size(), std::size_t{3} * 2 * 3);
}

std::string read_file(const std::string& path) {
    std::ifstream in(path, std::ios::binary);
    EXPECT_TRUE(in) << "cannot read " << path;
    std::ostringstream s;
    s << in.rdbuf();
    return s.str();
}

TEST(LocalContract, GeneratedFilesAreCurrent) {
    const std::string dir = PLUECKER_RTL_DIR;
    EXPECT_EQ(read_file(dir + "/" + kLocalContractSvFile), local_contract_sv_package())
        << dir << "/" << kLocalContractSvFile
        << " is not what the port contract generates: run 'pluecker contract --write rtl' (make contract)";
    EXPECT_EQ(read_file(dir + "/" + kLocalContractJsonFile), local_contract_json())
        << dir << "/" << kLocalContractJsonFile
        << " is not what the port contract generates: run 'pluecker contract --write rtl' (make contract)";
}

}  // namespace
}  // namespace pluecker
