// SPDX-License-Identifier: MIT
#include "pluecker/study.hpp"

#include "pluecker/boxtest.hpp"
#include "pluecker/f32unit.hpp"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <exception>
#include <functional>
#include <limits>
#include <memory>
#include <mutex>
#include <stdexcept>
#include <thread>

namespace pluecker {

// ---------------------------------------------------------------------------
// Counters

HitCounts& HitCounts::operator+=(const HitCounts& o) {
    queries += o.queries;
    exact_hits += o.exact_hits;
    hits += o.hits;
    false_hits += o.false_hits;
    false_misses += o.false_misses;
    return *this;
}

double HitCounts::false_hit_rate() const {
    const std::uint64_t misses = queries - exact_hits;
    return misses == 0 ? 0.0 : static_cast<double>(false_hits) / static_cast<double>(misses);
}

std::uint64_t wrong_pixels(const Image& a, const Image& b) {
    if (a.width != b.width || a.height != b.height)
        throw InputError("wrong_pixels: images of different sizes (" + std::to_string(a.width) + "x" +
                         std::to_string(a.height) + " and " + std::to_string(b.width) + "x" +
                         std::to_string(b.height) + ")");
    std::uint64_t n = 0;
    for (std::size_t i = 0; i + 2 < a.rgb.size(); i += 3)
        n += a.rgb[i] != b.rgb[i] || a.rgb[i + 1] != b.rgb[i + 1] || a.rgb[i + 2] != b.rgb[i + 2];
    return n;
}

double extra_percent(std::uint64_t value, std::uint64_t ref) {
    if (ref == 0) return value == 0 ? 0.0 : std::numeric_limits<double>::infinity();
    return 100.0 * (static_cast<double>(value) - static_cast<double>(ref)) / static_cast<double>(ref);
}

// ---------------------------------------------------------------------------
// Engines

namespace {

FixedFormat format_of(WidthPair w, FixedMode m) {
    FixedFormat f;
    f.coord_bits = w.coord_bits;
    f.dir_bits = w.dir_bits;
    f.mode = m;
    f.validate();
    return f;
}

RenderOptions fixed_options(const RenderOptions& base, WidthPair w, FixedMode m) {
    RenderOptions o = base;
    o.test = BoxTestKind::Fixed;
    o.fixed = format_of(w, m);
    o.progress = false;
    if (o.order == ChildOrder::Dist) check_combination(BoxTestKind::Fixed, o.order);
    return o;
}

// The fixed-point answer for a float ray on an already quantised box: a
// miss when the ray never meets the range cube.
bool setup_hit(const Ray& r, const FixedBox& b, const FixedFormat& f) {
    const std::optional<FixedRay> fr = fixed_setup_ray(r, f);
    return fr && fixed_hit(*fr, b, f);
}

// Answers every query with exact_hit; evaluates the float tests and every
// width pair on the same query.
class ReferenceEngine final : public BoxEngine {
public:
    ReferenceEngine(const Bvh& bvh, const std::vector<WidthPair>& widths) {
        for (const WidthPair& w : widths) {
            Format f{format_of(w, FixedMode::Conservative), format_of(w, FixedMode::Nearest), {}, {}};
            f.cons_boxes.reserve(bvh.nodes.size());
            f.near_boxes.reserve(bvh.nodes.size());
            for (const BvhNode& n : bvh.nodes) {
                f.cons_boxes.push_back(fixed_quantize_box(n.box, f.cons));
                f.near_boxes.push_back(fixed_quantize_box(n.box, f.near));
            }
            formats_.push_back(std::move(f));
            queries.push_back(WidthQueries{w, {}, {}, 0, 0});
        }
    }

    void test(std::span<const BoxQuery> batch, std::span<std::uint8_t> hits) override {
        for (std::size_t i = 0; i < batch.size(); ++i) {
            const Query& q = batch[i].query;
            const bool exact = exact_hit(q.ray, q.box);
            hits[i] = exact ? 1 : 0;
            checked.add(exact, exact);
            const bool pl = pluecker_hit(pluecker_setup(q.ray), q.box);
            pluecker.add(exact, pl);
            smits.add(exact, smits_hit(smits_setup(q.ray), q.box));
            f32.pluecker.add(exact, f32_pluecker_hit(q.ray, q.box, false));
            f32.pluecker_conservative.add(exact, f32_pluecker_hit(q.ray, q.box, true));
            f32.smits.add(exact, f32_smits_hit(q.ray, q.box));
            const std::uint32_t node = batch[i].node;
            for (std::size_t k = 0; k < formats_.size(); ++k) {
                const Format& f = formats_[k];
                WidthQueries& wq = queries[k];
                const bool c = setup_hit(q.ray, f.cons_boxes[node], f.cons);
                wq.conservative.add(exact, c);
                wq.fixed_hit_pluecker_miss += c && !pl;
                wq.fixed_miss_pluecker_hit += !c && pl;
                wq.nearest.add(exact, setup_hit(q.ray, f.near_boxes[node], f.near));
            }
        }
    }

    HitCounts checked, pluecker, smits;
    F32Counts f32;
    std::vector<WidthQueries> queries;

private:
    struct Format {
        FixedFormat cons, near;
        std::vector<FixedBox> cons_boxes, near_boxes;
    };
    std::vector<Format> formats_;
};

// Answers with fixed_hit (the RTL's answer) and counts the answers that
// differ from exact_hit.
class CheckingEngine final : public BoxEngine {
public:
    explicit CheckingEngine(const FixedFormat& f) : format_(f) {}
    void test(std::span<const BoxQuery> batch, std::span<std::uint8_t> hits) override {
        for (std::size_t i = 0; i < batch.size(); ++i) {
            const bool h = fixed_hit(batch[i].ray, batch[i].box, format_);
            hits[i] = h ? 1 : 0;
            checked.add(exact_hit(batch[i].query.ray, batch[i].query.box), h);
        }
    }
    HitCounts checked;

private:
    FixedFormat format_;
};

// Rays in flight for the study's renders: larger batches, same results.
constexpr std::size_t kStudyPool = 1024;

RenderOptions local_options(const RenderOptions& base, const LocalSpec& spec, FixedMode m) {
    RenderOptions o = base;
    o.test = BoxTestKind::Local;
    o.local = spec.format;
    o.local.mode = m;
    o.local.validate();
    o.local_build = spec.build;
    o.progress = false;
    o.pool = std::max(o.pool, kStudyPool);
    if (o.order == ChildOrder::Dist) check_combination(BoxTestKind::Local, o.order);
    return o;
}

// Answers every local query with exact_hit and evaluates every spec, in
// both modes, on the same query: the node's box and its parent's frame in
// that spec's hierarchy, the ray set up in that mode (the conservative
// set-up is the query's own: every spec shares the grid width).
class LocalReferenceEngine final : public LocalBoxEngine {
public:
    LocalReferenceEngine(const Accel& accel, const std::vector<LocalSpec>& specs) {
        for (const LocalSpec& sp : specs) {
            Spec s;
            for (const FixedMode m : {FixedMode::Conservative, FixedMode::Nearest}) {
                LocalFormat f = sp.format;
                f.mode = m;
                s.bvh[m == FixedMode::Nearest] = build_local_bvh(accel.nodes, f, sp.build);
            }
            specs_.push_back(std::move(s));
            LocalStudy ls;
            ls.spec = sp;
            ls.node_bits = specs_.back().bvh[0].memory_bits();
            out.push_back(ls);
        }
    }
    void test(std::span<const LocalBoxQuery> batch, std::span<std::uint8_t> hits) override {
        for (std::size_t i = 0; i < batch.size(); ++i) {
            const LocalBoxQuery& q = batch[i];
            const bool exact = exact_hit(q.query.ray, q.query.box);
            hits[i] = exact ? 1 : 0;
            checked.add(exact, exact);
            std::optional<LocalRay> near_ray;
            for (std::size_t k = 0; k < specs_.size(); ++k) {
                const LocalBvh& cons = specs_[k].bvh[0];
                out[k].conservative.add(exact, local_hit(local_node_ray(q.ray, cons.test_frame(q.node), cons.format),
                                                         cons.boxes[q.node], cons.format));
                const LocalBvh& near = specs_[k].bvh[1];
                if (!near_ray) near_ray = local_setup_ray(q.query.ray, near.format);  // meets the range: q.ray did
                out[k].nearest.add(exact, local_hit(local_node_ray(*near_ray, near.test_frame(q.node), near.format),
                                                    near.boxes[q.node], near.format));
            }
        }
    }
    HitCounts checked;
    std::vector<LocalStudy> out;

private:
    struct Spec {
        LocalBvh bvh[2];  // conservative, nearest
    };
    std::vector<Spec> specs_;
};

// Answers with local_hit (the RTL's answer) and counts the answers that
// differ from exact_hit.
class LocalCheckingEngine final : public LocalBoxEngine {
public:
    explicit LocalCheckingEngine(const LocalFormat& f) : format_(f) {}
    void test(std::span<const LocalBoxQuery> batch, std::span<std::uint8_t> hits) override {
        for (std::size_t i = 0; i < batch.size(); ++i) {
            const bool h = local_hit(batch[i].node_ray, batch[i].box, format_);
            hits[i] = h ? 1 : 0;
            checked.add(exact_hit(batch[i].query.ray, batch[i].query.box), h);
        }
    }
    HitCounts checked;

private:
    LocalFormat format_;
};

}  // namespace

ReferenceRun run_reference(const Mesh& mesh, const Bvh& bvh, const RenderOptions& opts,
                           const std::vector<WidthPair>& widths, int) {
    // Any format works: the engine ignores the quantised inputs of the
    // batched path and answers on the float query.
    RenderOptions o = fixed_options(opts, WidthPair{FixedFormat::kMaxBits, FixedFormat::kMaxBits},
                                    FixedMode::Conservative);
    o.pool = std::max(o.pool, kStudyPool);
    Accel accel(mesh, bvh);
    accel.quantize(o.fixed);
    const RenderScene scene(mesh, accel);
    ReferenceEngine engine(bvh, widths);
    ReferenceRun r;
    r.image = render_batched(scene, o, engine, r.figures.stats);
    r.figures.checked = engine.checked;
    r.pluecker = engine.pluecker;
    r.smits = engine.smits;
    r.f32 = engine.f32;
    r.queries = std::move(engine.queries);
    return r;
}

FixedRun run_fixed(const Mesh& mesh, const Bvh& bvh, const RenderOptions& opts, WidthPair w, FixedMode mode,
                   const Image* reference) {
    RenderOptions o = fixed_options(opts, w, mode);
    o.pool = std::max(o.pool, kStudyPool);
    Accel accel(mesh, bvh);
    accel.quantize(o.fixed);
    const RenderScene scene(mesh, accel);
    CheckingEngine engine(o.fixed);
    FixedRun r;
    r.image = render_batched(scene, o, engine, r.figures.stats);
    r.figures.checked = engine.checked;
    if (reference) r.figures.wrong_pixels = wrong_pixels(r.image, *reference);
    return r;
}

LocalReferenceRun run_local_reference(const Mesh& mesh, const Bvh& bvh, const RenderOptions& opts,
                                      const std::vector<LocalSpec>& specs) {
    if (specs.empty()) throw InputError("local frames: no configuration given");
    for (const LocalSpec& sp : specs)
        if (sp.format.grid_bits != specs.front().format.grid_bits)
            throw InputError("local frames: every configuration of a study needs the same --grid-bits");
    // The engine answers on the float query; the first spec's hierarchy
    // only drives the traversal (its ray set-up decides which rays meet the
    // grid's range, the same for every spec).
    const RenderOptions o = local_options(opts, specs.front(), FixedMode::Conservative);
    Accel accel(mesh, bvh);
    accel.localize(o.local, o.local_build);
    const RenderScene scene(mesh, accel);
    LocalReferenceEngine engine(accel, specs);
    LocalReferenceRun r;
    r.image = render_batched(scene, o, engine, r.figures.stats);
    r.figures.checked = engine.checked;
    r.specs = std::move(engine.out);
    return r;
}

FixedRun run_local(const Mesh& mesh, const Bvh& bvh, const RenderOptions& opts, const LocalSpec& spec,
                   FixedMode mode, const Image* reference) {
    const RenderOptions o = local_options(opts, spec, mode);
    Accel accel(mesh, bvh);
    accel.localize(o.local, o.local_build);
    const RenderScene scene(mesh, accel);
    LocalCheckingEngine engine(o.local);
    FixedRun r;
    r.image = render_batched(scene, o, engine, r.figures.stats);
    r.figures.checked = engine.checked;
    if (reference) r.figures.wrong_pixels = wrong_pixels(r.image, *reference);
    return r;
}

// ---------------------------------------------------------------------------
// The study

namespace {

double seconds_since(std::chrono::steady_clock::time_point t0) {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

}  // namespace

void run_tasks(std::vector<std::function<void()>>& tasks, int threads) {
    std::atomic<std::size_t> next{0};
    std::exception_ptr error;
    std::mutex m;
    auto work = [&] {
        for (;;) {
            const std::size_t i = next.fetch_add(1);
            if (i >= tasks.size()) return;
            try {
                tasks[i]();
            } catch (...) {
                std::lock_guard<std::mutex> lock(m);
                if (!error) error = std::current_exception();
                next = tasks.size();
            }
        }
    };
    const int n = std::max(1, std::min<int>(threads, static_cast<int>(tasks.size())));
    std::vector<std::thread> pool;
    for (int i = 1; i < n; ++i) pool.emplace_back(work);
    work();
    for (auto& t : pool) t.join();
    if (error) std::rethrow_exception(error);
}

namespace {

std::string pair_name(WidthPair w) { return std::to_string(w.coord_bits) + "x" + std::to_string(w.dir_bits); }

}  // namespace

StudyResult run_study(const Mesh& mesh, const Bvh& bvh, const StudyOptions& opts) {
    if (opts.widths.empty()) throw InputError("--widths: no width given");
    for (const WidthPair& w : opts.widths) format_of(w, FixedMode::Conservative);
    const auto t0 = std::chrono::steady_clock::now();
    StudyResult res;
    res.options = opts;
    const std::size_t nw = opts.widths.size();
    if (opts.work) res.work.resize(nw);
    if (opts.nearest) res.nearest.resize(nw);
    std::vector<Image> work_img(opts.work ? nw : 0), near_img(opts.nearest ? nw : 0);
    Image ref_img, direct_img;
    std::mutex log;
    auto say = [&](const std::string& s) {
        if (!opts.progress) return;
        std::lock_guard<std::mutex> lock(log);
        std::fprintf(stderr, "study: %6.1f s  %s\n", seconds_since(t0), s.c_str());
    };
    const int threads =
        opts.threads > 0 ? opts.threads : static_cast<int>(std::max(1u, std::thread::hardware_concurrency()));
    res.options.threads = threads;

    std::vector<std::function<void()>> tasks;
    tasks.push_back([&] {
        ReferenceRun r = run_reference(mesh, bvh, opts.render, opts.per_query ? opts.widths : std::vector<WidthPair>{},
                                       1);
        ref_img = std::move(r.image);
        res.reference = r.figures;
        res.pluecker = r.pluecker;
        res.smits = r.smits;
        res.f32 = r.f32;
        res.queries = std::move(r.queries);
        say("reference (exact answers): " + std::to_string(res.reference.stats.traversal.box_tests) +
            " box tests" + (opts.per_query ? ", per-query figures of " + std::to_string(nw) + " width pairs" : ""));
    });
    if (opts.direct_exact)
        tasks.push_back([&] {
            RenderOptions o = opts.render;
            o.test = BoxTestKind::Exact;
            o.threads = 1;
            o.progress = false;
            Accel accel(mesh, bvh);
            const RenderScene scene(mesh, accel);
            WorkFigures f;
            direct_img = render_direct(scene, o, f.stats);
            res.direct_exact = f;
            say("direct exact render: " + std::to_string(f.stats.traversal.box_tests) + " box tests");
        });
    for (std::size_t k = 0; k < nw; ++k) {
        if (opts.work)
            tasks.push_back([&, k] {
                FixedRun r = run_fixed(mesh, bvh, opts.render, opts.widths[k], FixedMode::Conservative, nullptr);
                work_img[k] = std::move(r.image);
                res.work[k] = r.figures;
                say(pair_name(opts.widths[k]) + " conservative: " +
                    std::to_string(r.figures.stats.traversal.box_tests) + " box tests");
            });
        if (opts.nearest)
            tasks.push_back([&, k] {
                FixedRun r = run_fixed(mesh, bvh, opts.render, opts.widths[k], FixedMode::Nearest, nullptr);
                near_img[k] = std::move(r.image);
                res.nearest[k] = r.figures;
                say(pair_name(opts.widths[k]) + " nearest: " + std::to_string(r.figures.checked.false_misses) +
                    " false misses");
            });
    }
    const std::size_t nl = opts.local.size();
    std::vector<Image> local_img(nl), local_near_img(nl);
    Image local_ref_img;
    if (nl) {
        res.local.resize(nl);
        tasks.push_back([&] {
            LocalReferenceRun r = run_local_reference(mesh, bvh, opts.render, opts.local);
            local_ref_img = std::move(r.image);
            res.local_reference = r.figures;
            for (std::size_t k = 0; k < nl; ++k) {
                res.local[k].spec = r.specs[k].spec;
                res.local[k].node_bits = r.specs[k].node_bits;
                res.local[k].conservative = r.specs[k].conservative;
                res.local[k].nearest = r.specs[k].nearest;
            }
            say("local reference (exact answers): " + std::to_string(r.figures.stats.traversal.box_tests) +
                " box tests, per-query figures of " + std::to_string(nl) + " local configurations");
        });
        for (std::size_t k = 0; k < nl; ++k) {
            tasks.push_back([&, k] {
                FixedRun r = run_local(mesh, bvh, opts.render, opts.local[k], FixedMode::Conservative, nullptr);
                local_img[k] = std::move(r.image);
                res.local[k].work = r.figures;
                say("local K=" + std::to_string(opts.local[k].format.box_bits) + " conservative: " +
                    std::to_string(r.figures.stats.traversal.box_tests) + " box tests");
            });
            tasks.push_back([&, k] {
                FixedRun r = run_local(mesh, bvh, opts.render, opts.local[k], FixedMode::Nearest, nullptr);
                local_near_img[k] = std::move(r.image);
                res.local[k].near = r.figures;
                say("local K=" + std::to_string(opts.local[k].format.box_bits) + " nearest: " +
                    std::to_string(r.figures.checked.false_misses) + " false misses");
            });
        }
    }
    run_tasks(tasks, threads);
    for (std::size_t k = 0; k < nl; ++k) {
        res.local[k].work.wrong_pixels = wrong_pixels(local_img[k], local_ref_img);
        res.local[k].near.wrong_pixels = wrong_pixels(local_near_img[k], local_ref_img);
    }
    // Images against the reference.
    if (res.direct_exact) res.direct_exact->wrong_pixels = wrong_pixels(direct_img, ref_img);
    for (std::size_t k = 0; k < work_img.size(); ++k) res.work[k].wrong_pixels = wrong_pixels(work_img[k], ref_img);
    for (std::size_t k = 0; k < near_img.size(); ++k)
        res.nearest[k].wrong_pixels = wrong_pixels(near_img[k], ref_img);
    res.seconds = seconds_since(t0);
    return res;
}

// ---------------------------------------------------------------------------
// JSON

namespace {

nlohmann::json counts_json(const HitCounts& c) {
    return {{"queries", c.queries},
            {"exact_hits", c.exact_hits},
            {"exact_misses", c.queries - c.exact_hits},
            {"hits", c.hits},
            {"false_hits", c.false_hits},
            {"false_misses", c.false_misses},
            {"false_hit_rate", c.false_hit_rate()}};
}

double per_ray(std::uint64_t v, std::uint64_t rays) {
    return rays == 0 ? 0.0 : static_cast<double>(v) / static_cast<double>(rays);
}

std::uint64_t total_rays(const RenderStats& s) {
    std::uint64_t n = 0;
    for (const auto r : s.rays) n += r;
    return n;
}

nlohmann::json rays_json(const RenderStats& s) {
    nlohmann::json j;
    for (int k = 0; k < kRayKinds; ++k) j[ray_kind_name(static_cast<RayKind>(k))] = s.rays[k];
    j["total"] = total_rays(s);
    return j;
}

}  // namespace

nlohmann::json work_json(const WorkFigures& f, const WorkFigures* ref, std::uint64_t pixels) {
    const TraversalStats& t = f.stats.traversal;
    const std::uint64_t rays = total_rays(f.stats);
    nlohmann::json j = {
        {"rays", rays_json(f.stats)},
        {"node_visits", t.node_visits},
        {"box_tests", t.box_tests},
        {"triangle_tests", t.tri_tests},
        {"per_ray",
         {{"node_visits", per_ray(t.node_visits, rays)},
          {"box_tests", per_ray(t.box_tests, rays)},
          {"triangle_tests", per_ray(t.tri_tests, rays)}}},
        {"render_ms", f.stats.render_ms},
        {"wrong_pixels", f.wrong_pixels},
        {"wrong_pixel_fraction", pixels == 0 ? 0.0 : static_cast<double>(f.wrong_pixels) / static_cast<double>(pixels)},
    };
    if (f.checked.queries) j["checked"] = counts_json(f.checked);
    if (ref) {
        const TraversalStats& r = ref->stats.traversal;
        const std::uint64_t rr = total_rays(ref->stats);
        j["extra_percent"] = {{"node_visits", extra_percent(t.node_visits, r.node_visits)},
                              {"box_tests", extra_percent(t.box_tests, r.box_tests)},
                              {"triangle_tests", extra_percent(t.tri_tests, r.tri_tests)}};
        // Differs from extra_percent only when the ray set differs (nearest mode).
        auto pr = [&](std::uint64_t v, std::uint64_t rv) {
            const double a = per_ray(v, rays), b = per_ray(rv, rr);
            return b == 0.0 ? 0.0 : 100.0 * (a - b) / b;
        };
        j["extra_percent_per_ray"] = {{"node_visits", pr(t.node_visits, r.node_visits)},
                                      {"box_tests", pr(t.box_tests, r.box_tests)},
                                      {"triangle_tests", pr(t.tri_tests, r.tri_tests)}};
    }
    return j;
}

namespace {

const char* kDefinitions[][2] = {
    {"reference",
     "the batched fixed-point traversal (same pixels, ray trees and ray clipping as the fixed test) with every box "
     "query answered by exact_hit on its float ray and box"},
    {"false_miss", "exact_hit true, the test false"},
    {"false_hit", "exact_hit false, the test true"},
    {"false_hit_rate", "false hits / exact misses"},
    {"extra_percent", "100 * (count - count_reference) / count_reference, counts summed over all rays of the render "
                      "(camera, shadow, reflection, refraction); box_tests is the main figure (the RTL does one box "
                      "test per clock)"},
    {"extra_percent_per_ray", "the same on the mean per ray (equal to extra_percent when the ray set is the "
                              "reference's, as in conservative mode)"},
    {"wrong_pixels", "pixels whose 8-bit RGB differs in any byte from the reference image"},
    {"queries", "per-query figures on the reference's box queries (rays clipped as the fixed test sees them)"},
    {"checked", "the render's own box queries against exact_hit"},
    {"local", "local frames (local.hpp): each configuration against the local reference, the same batched "
              "traversal on the local path with exact answers (rays skipped when they miss the local grid's range); "
              "memory: bits per node of the quantised hierarchy against the float node's 256"},
};

}  // namespace

nlohmann::json run_header_json(const Mesh& mesh, const Bvh& bvh, BuildMethod build, const RenderOptions& o,
                               int threads, double seconds) {
    nlohmann::json j;
    j["scene"] = mesh.name;
    j["triangles"] = mesh.triangles.size();
    j["build"] = method_name(build);
    j["bvh"] = {{"nodes", bvh.nodes.size()}, {"leaves", bvh.leaf_count()}, {"depth", bvh.depth()}};
    j["order"] = order_name(o.order);
    j["width"] = o.width;
    j["height"] = o.height;
    j["max_depth"] = o.max_depth;
    j["threads"] = threads;
    j["seconds"] = seconds;
    return j;
}

nlohmann::json study_json(const StudyResult& r, const Mesh& mesh, const Bvh& bvh, BuildMethod build) {
    const RenderOptions& o = r.options.render;
    const std::uint64_t pixels = static_cast<std::uint64_t>(o.width) * static_cast<std::uint64_t>(o.height);
    nlohmann::json j = run_header_json(mesh, bvh, build, o, r.options.threads, r.seconds);
    nlohmann::json defs;
    for (const auto& d : kDefinitions) defs[d[0]] = d[1];
    j["definitions"] = defs;
    j["reference"] = work_json(r.reference, nullptr, pixels);
    if (r.direct_exact) j["direct_exact"] = work_json(*r.direct_exact, &r.reference, pixels);
    if (r.options.per_query) {
        j["queries"] = {{"count", r.reference.checked.queries},
                        {"exact_hits", r.reference.checked.exact_hits},
                        {"exact_misses", r.reference.checked.queries - r.reference.checked.exact_hits},
                        {"pluecker", counts_json(r.pluecker)},
                        {"smits", counts_json(r.smits)},
                        {"f32_pluecker", counts_json(r.f32.pluecker)},
                        {"f32_pluecker_conservative", counts_json(r.f32.pluecker_conservative)},
                        {"f32_smits", counts_json(r.f32.smits)}};
    }
    nlohmann::json widths = nlohmann::json::array();
    for (std::size_t k = 0; k < r.options.widths.size(); ++k) {
        const WidthPair w = r.options.widths[k];
        nlohmann::json e = {{"coord_bits", w.coord_bits}, {"dir_bits", w.dir_bits}};
        if (k < r.queries.size()) {
            const WidthQueries& q = r.queries[k];
            e["query"] = {{"conservative", counts_json(q.conservative)},
                          {"nearest", counts_json(q.nearest)},
                          {"vs_pluecker",
                           {{"fixed_hit_pluecker_miss", q.fixed_hit_pluecker_miss},
                            {"fixed_miss_pluecker_hit", q.fixed_miss_pluecker_hit}}}};
        }
        if (k < r.work.size()) e["work"] = work_json(r.work[k], &r.reference, pixels);
        if (k < r.nearest.size()) e["nearest"] = work_json(r.nearest[k], &r.reference, pixels);
        widths.push_back(e);
    }
    j["widths"] = widths;
    if (r.local_reference) {
        nlohmann::json l;
        l["grid_bits"] = r.options.local.front().format.grid_bits;
        l["reference"] = work_json(*r.local_reference, nullptr, pixels);
        l["float_node_bits"] = LocalBvh::kFloatNodeBits;
        const double tris = static_cast<double>(mesh.triangles.size());
        nlohmann::json configs = nlohmann::json::array();
        for (const LocalStudy& s : r.local) {
            const LocalFormat& f = s.spec.format;
            const double nodes = static_cast<double>(bvh.nodes.size());
            configs.push_back({{"box_bits", f.box_bits},
                               {"dir_bits", f.dir_bits},
                               {"grid_bits", f.grid_bits},
                               {"cells", s.spec.build.uniform ? "uniform" : "axis"},
                               {"frames", s.spec.build.parent_origin ? "parent" : "own"},
                               {"node_bits", s.node_bits},
                               {"memory",
                                {{"bytes_per_node", s.node_bits / 8.0},
                                 {"bytes_per_triangle", tris > 0 ? nodes * s.node_bits / 8.0 / tris : 0.0},
                                 {"float_bytes_per_triangle", tris > 0 ? nodes * 32.0 / tris : 0.0},
                                 {"fraction_of_float", double(s.node_bits) / LocalBvh::kFloatNodeBits}}},
                               {"query", {{"conservative", counts_json(s.conservative)},
                                          {"nearest", counts_json(s.nearest)}}},
                               {"work", work_json(s.work, &*r.local_reference, pixels)},
                               {"nearest", work_json(s.near, &*r.local_reference, pixels)}});
        }
        l["configs"] = configs;
        j["local"] = l;
    }
    return j;
}

// ---------------------------------------------------------------------------
// Plan

void check_max_extra_work(double p) {
    if (!(p >= 0.0) || !std::isfinite(p))
        throw InputError("option --max-extra-work: must be a finite number >= 0 (percent), got " +
                         std::to_string(p));
}

// Measures the candidates in order (conservative renders) until one's
// extra box tests over `reference` are <= max_extra_percent; returns its
// index into `steps`, which holds every step measured.
template <class Step, class Candidate, class Measure>
std::optional<std::size_t> first_within(const std::vector<Candidate>& candidates, double max_extra_percent,
                                        const WorkFigures& reference, std::vector<Step>& steps,
                                        const std::function<void(const Step&)>& on_step, Measure measure) {
    for (const Candidate& c : candidates) {
        Step s{c, measure(c), 0.0};  // PlanStep::widths or LocalPlanStep::spec first
        s.extra_box_tests_percent =
            extra_percent(s.work.stats.traversal.box_tests, reference.stats.traversal.box_tests);
        steps.push_back(s);
        if (on_step) on_step(s);
        if (s.extra_box_tests_percent <= max_extra_percent) return steps.size() - 1;
    }
    return std::nullopt;
}

PlanResult plan_widths(const Mesh& mesh, const Bvh& bvh, const RenderOptions& opts,
                       const std::vector<WidthPair>& widths, double max_extra_percent,
                       const std::function<void(const PlanStep&)>& on_step) {
    check_max_extra_work(max_extra_percent);
    if (widths.empty()) throw InputError("--widths: no width given");
    PlanResult res;
    res.reference = run_reference(mesh, bvh, opts, {}, 1).figures;
    res.chosen = first_within(widths, max_extra_percent, res.reference, res.steps, on_step, [&](const WidthPair& w) {
        return run_fixed(mesh, bvh, opts, w, FixedMode::Conservative, nullptr).figures;
    });
    return res;
}

LocalPlanResult plan_local(const Mesh& mesh, const Bvh& bvh, const RenderOptions& opts,
                           const std::vector<LocalSpec>& specs, double max_extra_percent,
                           const std::function<void(const LocalPlanStep&)>& on_step) {
    check_max_extra_work(max_extra_percent);
    if (specs.empty()) throw InputError("--local: no box width given");
    LocalPlanResult res;
    for (const LocalSpec& sp : specs)
        if (sp.format.grid_bits != specs.front().format.grid_bits)
            throw InputError("local frames: every configuration of a plan needs the same --grid-bits");
    // The reference's answers are exact; the first spec drives its traversal.
    res.reference = run_local_reference(mesh, bvh, opts, {specs.front()}).figures;
    res.chosen = first_within(specs, max_extra_percent, res.reference, res.steps, on_step, [&](const LocalSpec& sp) {
        return run_local(mesh, bvh, opts, sp, FixedMode::Conservative, nullptr).figures;
    });
    return res;
}

}  // namespace pluecker
