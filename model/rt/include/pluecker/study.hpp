// SPDX-License-Identifier: MIT
// The speed-for-accuracy study of the fixed-point box test: what narrower
// widths (COORD_BITS, DIR_BITS) cost in traversal work and image accuracy,
// measured on a render of a scene (`pluecker study`, `pluecker plan`).
//
// The reference traversal
//   The fixed-point path (traverse.hpp) sets every ray up once (a ray
//   from outside the range cube is clipped exactly onto it, one that misses
//   the cube is not traced) and issues its box queries on the ray as given,
//   tmax shrunk to the best hit. The reference is that same batched
//   traversal (render_batched, same pixels, same ray trees) with every box
//   query answered by exact_hit on the query's float ray and box: an exact
//   test in place of the RTL. Its box queries are the queries the hardware
//   would see if it answered exactly; every per-query figure is measured on
//   them, and every traversal figure is compared with its counts. (The
//   direct exact render, render_direct with the exact test, is reported
//   beside it: same image, and box tests that differ only by the root test
//   of rays that miss the range cube, which the fixed-point path skips.)
//
// Per query (on the reference's box queries)
//   For each width pair and mode, fixed_setup_ray + fixed_quantize_box +
//   fixed_hit; float pluecker_hit and smits_hit on the same queries, and
//   the binary32 units' models (f32unit.hpp: the Plücker unit rounded to
//   nearest and conservative, the slab unit).
//     false miss       exact_hit true,  the test false
//     false hit        exact_hit false, the test true
//     false-hit rate   false hits / exact misses (the share of boxes the
//                      ray misses that the test lets through)
//   Conservative mode must have no false miss (fixed.hpp's margin bound).
//
// Per ray work (renders)
//   For each width pair, a conservative render (render_batched, every
//   answer fixed_hit) is compared with the reference:
//     extra work [%] = 100 * (count_W - count_ref) / count_ref
//   for count = box tests (the main figure: the RTL performs one box test
//   per clock, so it is the hardware time per ray), node visits and
//   triangle tests, each summed over all rays of the render (camera,
//   shadow, reflection, refraction). A conservative test never misses, so
//   every ray finds the same hit and the ray set is the reference's: the
//   relative increase of the totals is the relative increase of the mean
//   per ray. Per ray figures are totals / rays.
//
// Nearest mode (renders)
//   For each width pair a render with nearest rounding (no margin): wrong
//   pixels = pixels whose 8-bit RGB differs in any byte from the reference
//   image; false misses / false hits = box queries of that render whose
//   answer differs from exact_hit on the same query.
#pragma once

#include "pluecker/bvh.hpp"
#include "pluecker/fixed.hpp"
#include "pluecker/image.hpp"
#include "pluecker/mesh.hpp"
#include "pluecker/render.hpp"
#include "pluecker/traverse.hpp"

#include <nlohmann/json.hpp>

#include <cstdint>
#include <functional>
#include <optional>
#include <string>
#include <vector>

namespace pluecker {

struct WidthPair {
    int coord_bits = 16;
    int dir_bits = 16;
    bool operator==(const WidthPair&) const = default;
};

// Answers of one test on a set of queries, against exact_hit.
struct HitCounts {
    std::uint64_t queries = 0;
    std::uint64_t exact_hits = 0;
    std::uint64_t hits = 0;
    std::uint64_t false_hits = 0;
    std::uint64_t false_misses = 0;
    void add(bool exact, bool test) {
        ++queries;
        exact_hits += exact;
        hits += test;
        false_hits += test && !exact;
        false_misses += exact && !test;
    }
    HitCounts& operator+=(const HitCounts& o);
    // false hits / exact misses (0 when there is no exact miss).
    double false_hit_rate() const;
};

// The binary32 units (f32unit.hpp) on a set of queries, against exact_hit.
struct F32Counts {
    HitCounts pluecker;               // f32_pluecker_hit, round to nearest
    HitCounts pluecker_conservative;  // f32_pluecker_hit, outward rounding
    HitCounts smits;                  // f32_smits_hit
};

// The per-query figures of one width pair.
struct WidthQueries {
    WidthPair widths;
    HitCounts conservative;
    HitCounts nearest;
    // Conservative fixed answer against float pluecker on the same query.
    std::uint64_t fixed_hit_pluecker_miss = 0;
    std::uint64_t fixed_miss_pluecker_hit = 0;
};

// One render's traversal figures.
struct WorkFigures {
    RenderStats stats;
    HitCounts checked;              // its box queries against exact_hit
    std::uint64_t wrong_pixels = 0; // against the reference image
};

// One local-frame configuration of the study (local.hpp): its format (the
// mode is set per run) and hierarchy options.
struct LocalSpec {
    LocalFormat format;
    LocalBuildOptions build;
};

// The figures of one local configuration.
struct LocalStudy {
    LocalSpec spec;
    int node_bits = 0;                  // LocalBvh::memory_bits
    HitCounts conservative, nearest;    // per query, on the local reference's queries
    WorkFigures work;                   // conservative render
    WorkFigures near;                   // nearest render
};

struct StudyOptions {
    RenderOptions render;               // size, order, camera, lights; test/fixed are set per run
    std::vector<WidthPair> widths;      // at least one
    std::vector<LocalSpec> local;       // local-frame configurations (one grid width for all)
    bool per_query = true;              // 1a
    bool work = true;                   // 1b
    bool nearest = true;                // 1c
    bool direct_exact = true;           // the direct exact render beside the reference
    int threads = 0;                    // 0: std::thread::hardware_concurrency()
    bool progress = false;              // lines on stderr
};

struct StudyResult {
    StudyOptions options;
    WorkFigures reference;              // exact answers on the fixed-point path
    std::optional<WorkFigures> direct_exact;
    HitCounts pluecker;                 // float tests on the reference queries
    HitCounts smits;
    F32Counts f32;                      // the binary32 units on the reference queries
    std::vector<WidthQueries> queries;  // per width (empty without per_query)
    std::vector<WorkFigures> work;      // per width, conservative (empty without work)
    std::vector<WorkFigures> nearest;   // per width, nearest (empty without nearest)
    // Local frames: the reference on the local path (exact answers; rays
    // skipped when they miss the local grid's range), and per configuration.
    std::optional<WorkFigures> local_reference;
    std::vector<LocalStudy> local;
    double seconds = 0;
};

// The reference render (exact answers on the batched fixed-point path).
// With `widths`, also the per-query figures of each width (and of the
// float tests). Needs nothing quantised: it quantises its own copy.
struct ReferenceRun {
    Image image;
    WorkFigures figures;
    HitCounts pluecker, smits;
    F32Counts f32;
    std::vector<WidthQueries> queries;
};
ReferenceRun run_reference(const Mesh& mesh, const Bvh& bvh, const RenderOptions& opts,
                           const std::vector<WidthPair>& widths, int threads);

// A render through the batched path with the fixed test in `mode`, every
// answer checked against exact_hit; wrong pixels against `reference` (when
// given, else 0).
struct FixedRun {
    Image image;
    WorkFigures figures;
};
FixedRun run_fixed(const Mesh& mesh, const Bvh& bvh, const RenderOptions& opts, WidthPair w, FixedMode mode,
                   const Image* reference);

// The local path's reference render (every box query answered by
// exact_hit) and the per-query figures of every spec on its queries. All
// specs must share one grid width (InputError otherwise).
struct LocalReferenceRun {
    Image image;
    WorkFigures figures;
    std::vector<LocalStudy> specs;  // conservative and nearest per query filled in
};
LocalReferenceRun run_local_reference(const Mesh& mesh, const Bvh& bvh, const RenderOptions& opts,
                                      const std::vector<LocalSpec>& specs);
// A render through the local path in `mode`, every answer checked against
// exact_hit; wrong pixels against `reference` when given.
FixedRun run_local(const Mesh& mesh, const Bvh& bvh, const RenderOptions& opts, const LocalSpec& spec,
                   FixedMode mode, const Image* reference);

// Pixels whose RGB bytes differ (images of the same size; InputError otherwise).
std::uint64_t wrong_pixels(const Image& a, const Image& b);

// 100 * (value - ref) / ref; 0 when both are 0.
double extra_percent(std::uint64_t value, std::uint64_t ref);

// The scene, BVH, render settings, threads and run time of a study's JSON
// (study_json, cascade_study_json).
nlohmann::json run_header_json(const Mesh& mesh, const Bvh& bvh, BuildMethod build, const RenderOptions& o,
                               int threads, double seconds);

// Runs the tasks on up to `threads` threads (at least one); the first
// exception is rethrown after all have stopped.
void run_tasks(std::vector<std::function<void()>>& tasks, int threads);

// One render's traversal figures as JSON, with the extra work against `ref`
// when given (pixels: the image's, for the wrong-pixel fraction).
nlohmann::json work_json(const WorkFigures& f, const WorkFigures* ref, std::uint64_t pixels);

// The whole study; renders run on up to `threads` threads at once.
StudyResult run_study(const Mesh& mesh, const Bvh& bvh, const StudyOptions& opts);

// Every figure, with the definitions above as text.
nlohmann::json study_json(const StudyResult& r, const Mesh& mesh, const Bvh& bvh, BuildMethod build);

// ---------------------------------------------------------------------------
// Plan: the first width pair (in the given order, normally increasing)
// whose conservative extra box-test work is <= max_extra_percent.

// Throws InputError naming --max-extra-work unless p >= 0 and finite.
void check_max_extra_work(double p);

struct PlanStep {
    WidthPair widths;
    WorkFigures work;
    double extra_box_tests_percent = 0;
};
struct PlanResult {
    WorkFigures reference;
    std::vector<PlanStep> steps;   // measured, in order, up to the chosen one
    std::optional<std::size_t> chosen;  // index into steps; empty when no width meets the bound
};
// `on_step` (optional) is called after each measured width.
PlanResult plan_widths(const Mesh& mesh, const Bvh& bvh, const RenderOptions& opts,
                       const std::vector<WidthPair>& widths, double max_extra_percent,
                       const std::function<void(const PlanStep&)>& on_step = {});

// The same for local frames: the first spec (in the given order, normally
// increasing K) whose conservative extra box tests over the local path's
// exact reference are <= max_extra_percent. Specs share one grid width.
struct LocalPlanStep {
    LocalSpec spec;
    WorkFigures work;
    double extra_box_tests_percent = 0;
};
struct LocalPlanResult {
    WorkFigures reference;
    std::vector<LocalPlanStep> steps;
    std::optional<std::size_t> chosen;
};
LocalPlanResult plan_local(const Mesh& mesh, const Bvh& bvh, const RenderOptions& opts,
                           const std::vector<LocalSpec>& specs, double max_extra_percent,
                           const std::function<void(const LocalPlanStep&)>& on_step = {});

}  // namespace pluecker
