// SPDX-License-Identifier: MIT
// The cascade on traversal queries (pluecker/cascade.hpp): narrow ternary
// units escalating their uncertain answers to a wide one, on a render of a
// small scene, every answer checked against the exact test.
#include "pluecker/cascade.hpp"

#include "pluecker/bvh.hpp"
#include "pluecker/mesh.hpp"

#include <gtest/gtest.h>

#include <string>

namespace pluecker {
namespace {

CascadeStudyResult small_cascade(std::vector<WidthPair> narrow, WidthPair wide) {
    static const Mesh mesh = make_scene("sphere:2000");
    static const Bvh bvh = build_bvh(mesh, BuildOptions{});
    CascadeStudyOptions o;
    o.render.width = o.render.height = 32;
    o.render.order = ChildOrder::Dsa;
    o.narrow = std::move(narrow);
    o.wide = wide;
    o.threads = 2;
    return run_cascade_study(mesh, bvh, o);
}

TEST(CascadeStudy, NoRealHitLostAndDoubtsFallWithWidth) {
    const CascadeStudyResult r = small_cascade({{6, 6}, {8, 8}, {10, 10}, {12, 12}}, {16, 16});
    ASSERT_EQ(r.rows.size(), 4u);
    double last = 1.0;
    for (const CascadeStudyRow& row : r.rows) {
        SCOPED_TRACE(row.narrow.coord_bits);
        const CascadeCounts& c = row.run.counts;
        ASSERT_GT(c.queries, 1000u);
        // Every query is one of the three answers; each checked.
        EXPECT_EQ(c.certain_hits + c.certain_misses + c.escalated, c.queries);
        EXPECT_EQ(c.checked, c.queries);
        // The promise: no real hit lost, no certain hit false, the image the
        // reference's.
        EXPECT_EQ(c.false_misses, 0u);
        EXPECT_EQ(c.false_certain_hits, 0u);
        EXPECT_EQ(row.wrong_pixels, 0u);
        // Wider narrow units doubt less.
        EXPECT_LT(c.escalated_fraction(), last);
        last = c.escalated_fraction();
        // The cascade does the wide width's work, the narrow width alone more.
        ASSERT_TRUE(row.alone.has_value() && r.wide_alone.has_value());
        EXPECT_EQ(row.run.stats.traversal.box_tests, r.wide_alone->stats.traversal.box_tests);
        EXPECT_GE(row.alone->stats.traversal.box_tests, row.run.stats.traversal.box_tests);
    }
    EXPECT_GT(r.rows.front().run.counts.escalated_fraction(), 0.3);  // 6/6 doubts a lot
}

TEST(CascadeStudy, NarrowMustBeNarrower) {
    EXPECT_THROW(small_cascade({{16, 16}}, {16, 16}), InputError);
    EXPECT_THROW(small_cascade({}, {16, 16}), InputError);
    EXPECT_THROW(small_cascade({{5, 8}}, {16, 16}), InputError);
}

}  // namespace
}  // namespace pluecker
