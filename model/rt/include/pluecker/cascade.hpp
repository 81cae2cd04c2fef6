// SPDX-License-Identifier: MIT
// The cascade on traversal queries: a narrow ternary format answers every
// box query of a render, and the queries it is not sure about are re-tested
// by a wide conservative format (ternary.hpp; rtl/pluecker_cascade.sv is the
// hardware). `pluecker cascade` measures, per scene and narrow width:
//
//   escalated [%]   uncertain narrow answers / box queries of the cascade
//                   render: the share of the narrow units' queries that a
//                   wide unit must test again
//   certain hits, certain misses   the narrow answers that stand
//   extra work [%]  box tests of the cascade render against the reference
//                   (exact answers on the same batched path, study.hpp), as
//                   in `pluecker study`; beside it the narrow width alone and
//                   the wide width alone (conservative renders)
//   checked         every cascade answer against exact_hit on the query's
//                   float ray and box: no real hit may be lost and no certain
//                   hit may be false (both counted, both must be 0), and the
//                   image must equal the reference's
//
// Effective box tests per second of a chip follow from these (scripts/
// chip_report.py): a chip with L narrow lanes and W wide units at one clock
// F answers min(L, W / escalated) * F narrow queries per second, and
// reference box tests per second are that times reference / cascade box
// tests.
#pragma once

#include "pluecker/batched.hpp"
#include "pluecker/bvh.hpp"
#include "pluecker/image.hpp"
#include "pluecker/mesh.hpp"
#include "pluecker/render.hpp"
#include "pluecker/study.hpp"
#include "pluecker/ternary.hpp"

#include <nlohmann/json.hpp>

#include <cstdint>
#include <vector>

namespace pluecker {

// The answers of a cascade on a set of queries.
struct CascadeCounts {
    std::uint64_t queries = 0;         // narrow queries (box tests of the render)
    std::uint64_t certain_hits = 0;    // narrow Hit
    std::uint64_t certain_misses = 0;  // narrow Miss
    std::uint64_t escalated = 0;       // narrow Uncertain: tested again by the wide format
    std::uint64_t wide_hits = 0;       // escalated queries the wide format calls hits
    std::uint64_t hits = 0;            // the cascade's hits
    // Against exact_hit (when checked):
    std::uint64_t checked = 0;
    std::uint64_t exact_hits = 0;
    std::uint64_t false_hits = 0;          // cascade hit, no real hit (wide false hits)
    std::uint64_t false_misses = 0;        // a real hit lost: must be 0
    std::uint64_t false_certain_hits = 0;  // narrow Hit, no real hit: must be 0
    void add(const CascadeAnswer& a);
    void add_exact(const CascadeAnswer& a, bool exact);
    double escalated_fraction() const;
};

// A BoxEngine answering through the cascade: each query is set up at both
// widths from its float ray; the boxes of the BVH are quantised once per
// width. With `check`, every answer is compared with exact_hit.
class CascadeBoxEngine final : public BoxEngine {
public:
    CascadeBoxEngine(const Bvh& bvh, const CascadeFormats& f, bool check);
    void test(std::span<const BoxQuery> batch, std::span<std::uint8_t> hits) override;
    const CascadeCounts& counts() const { return counts_; }

private:
    CascadeFormats formats_;
    bool check_;
    std::vector<FixedBox> narrow_boxes_, wide_boxes_;
    CascadeCounts counts_;
};

// A render through the batched path answered by the cascade (the traversal
// itself runs on the wide format, as the wide unit would set it up).
struct CascadeRun {
    Image image;
    RenderStats stats;
    CascadeCounts counts;
};
CascadeRun run_cascade(const Mesh& mesh, const Bvh& bvh, const RenderOptions& opts, const CascadeFormats& f,
                       bool check);

struct CascadeStudyOptions {
    RenderOptions render;
    std::vector<WidthPair> narrow;  // at least one
    WidthPair wide{16, 16};
    bool check = true;      // every answer against exact_hit
    bool alone = true;      // the narrow and wide widths alone (conservative renders)
    int threads = 0;        // 0: std::thread::hardware_concurrency()
    bool progress = false;  // lines on stderr
};

struct CascadeStudyRow {
    WidthPair narrow;
    CascadeRun run;                    // image dropped after the comparison
    std::uint64_t wrong_pixels = 0;    // against the reference image
    std::optional<WorkFigures> alone;  // the narrow width alone
};

struct CascadeStudyResult {
    CascadeStudyOptions options;
    WorkFigures reference;
    std::optional<WorkFigures> wide_alone;
    std::vector<CascadeStudyRow> rows;
    double seconds = 0;
};

// InputError for an empty width list, a width outside 6..24, or a narrow
// width that is not narrower than the wide one in both fields.
CascadeStudyResult run_cascade_study(const Mesh& mesh, const Bvh& bvh, const CascadeStudyOptions& opts);
// The answer counts of a cascade run (queries, certain hits and misses,
// escalated, hits; with "checked" the comparison with the exact test).
nlohmann::json cascade_counts_json(const CascadeCounts& c);
nlohmann::json cascade_study_json(const CascadeStudyResult& r, const Mesh& mesh, const Bvh& bvh, BuildMethod build);

}  // namespace pluecker
