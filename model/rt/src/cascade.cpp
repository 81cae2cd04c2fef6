// SPDX-License-Identifier: MIT
// The cascade on traversal queries (cascade.hpp).
#include "pluecker/cascade.hpp"

#include "pluecker/boxtest.hpp"

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <functional>
#include <mutex>
#include <optional>
#include <string>
#include <thread>

namespace pluecker {

void CascadeCounts::add(const CascadeAnswer& a) {
    ++queries;
    certain_hits += a.narrow == TernaryAnswer::Hit;
    certain_misses += a.narrow == TernaryAnswer::Miss;
    escalated += a.escalated();
    wide_hits += a.escalated() && a.hit;
    hits += a.hit;
}

void CascadeCounts::add_exact(const CascadeAnswer& a, bool exact) {
    ++checked;
    exact_hits += exact;
    false_hits += a.hit && !exact;
    false_misses += exact && !a.hit;
    false_certain_hits += a.narrow == TernaryAnswer::Hit && !exact;
}

double CascadeCounts::escalated_fraction() const {
    return queries == 0 ? 0.0 : static_cast<double>(escalated) / static_cast<double>(queries);
}

namespace {

std::vector<FixedBox> quantize_boxes(const Bvh& bvh, const FixedFormat& f) {
    std::vector<FixedBox> out;
    out.reserve(bvh.nodes.size());
    for (const BvhNode& n : bvh.nodes) out.push_back(fixed_quantize_box(n.box, f));
    return out;
}

FixedFormat conservative(WidthPair w) {
    FixedFormat f;
    f.coord_bits = w.coord_bits;
    f.dir_bits = w.dir_bits;
    f.validate();
    return f;
}

std::string pair_text(WidthPair w) { return std::to_string(w.coord_bits) + "x" + std::to_string(w.dir_bits); }

}  // namespace

CascadeBoxEngine::CascadeBoxEngine(const Bvh& bvh, const CascadeFormats& f, bool check)
    : formats_(f), check_(check) {
    formats_.validate();
    narrow_boxes_ = quantize_boxes(bvh, formats_.narrow);
    wide_boxes_ = quantize_boxes(bvh, formats_.wide);
}

void CascadeBoxEngine::test(std::span<const BoxQuery> batch, std::span<std::uint8_t> hits) {
    for (std::size_t i = 0; i < batch.size(); ++i) {
        const BoxQuery& q = batch[i];
        const std::optional<FixedRay> nr = fixed_setup_ray(q.query.ray, formats_.narrow);
        const std::optional<FixedRay> wr = fixed_setup_ray(q.query.ray, formats_.wide);
        CascadeAnswer a;  // a miss when the ray never meets the narrow range cube (it holds every box)
        if (nr && wr) a = cascade_answer(*nr, narrow_boxes_[q.node], *wr, wide_boxes_[q.node], formats_);
        hits[i] = a.hit ? 1 : 0;
        counts_.add(a);
        if (check_) counts_.add_exact(a, exact_hit(q.query.ray, q.query.box));
    }
}

CascadeRun run_cascade(const Mesh& mesh, const Bvh& bvh, const RenderOptions& opts, const CascadeFormats& f,
                       bool check) {
    RenderOptions o = opts;
    o.test = BoxTestKind::Fixed;
    o.fixed = f.wide;
    o.progress = false;
    Accel accel(mesh, bvh);
    accel.quantize(o.fixed);
    const RenderScene scene(mesh, accel);
    CascadeBoxEngine engine(bvh, f, check);
    CascadeRun r;
    r.image = render_batched(scene, o, engine, r.stats);
    r.counts = engine.counts();
    return r;
}

CascadeStudyResult run_cascade_study(const Mesh& mesh, const Bvh& bvh, const CascadeStudyOptions& opts) {
    if (opts.narrow.empty()) throw InputError("--narrow: no width given");
    const FixedFormat wide = conservative(opts.wide);
    for (const WidthPair& w : opts.narrow) {
        conservative(w);
        if (w.coord_bits > opts.wide.coord_bits || w.dir_bits > opts.wide.dir_bits || w == opts.wide)
            throw InputError("--narrow: " + pair_text(w) + " is not narrower than the wide width " +
                             pair_text(opts.wide));
    }
    const auto t0 = std::chrono::steady_clock::now();
    auto seconds = [&] { return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count(); };
    std::mutex log;
    auto say = [&](const std::string& s) {
        if (!opts.progress) return;
        std::lock_guard<std::mutex> lock(log);
        std::fprintf(stderr, "cascade: %6.1f s  %s\n", seconds(), s.c_str());
    };
    CascadeStudyResult res;
    res.options = opts;
    res.options.threads =
        opts.threads > 0 ? opts.threads : static_cast<int>(std::max(1u, std::thread::hardware_concurrency()));
    res.rows.resize(opts.narrow.size());
    std::vector<Image> images(opts.narrow.size());
    Image ref_img;
    std::vector<std::function<void()>> tasks;
    tasks.push_back([&] {
        ReferenceRun r = run_reference(mesh, bvh, opts.render, {}, 1);
        ref_img = std::move(r.image);
        res.reference = r.figures;
        say("reference: " + std::to_string(res.reference.stats.traversal.box_tests) + " box tests");
    });
    if (opts.alone)
        tasks.push_back([&] {
            res.wide_alone = run_fixed(mesh, bvh, opts.render, opts.wide, FixedMode::Conservative, nullptr).figures;
            say(pair_text(opts.wide) + " alone: " + std::to_string(res.wide_alone->stats.traversal.box_tests) +
                " box tests");
        });
    for (std::size_t k = 0; k < opts.narrow.size(); ++k) {
        tasks.push_back([&, k] {
            const CascadeFormats f{conservative(opts.narrow[k]), wide};
            CascadeStudyRow& row = res.rows[k];
            row.narrow = opts.narrow[k];
            row.run = run_cascade(mesh, bvh, opts.render, f, opts.check);
            images[k] = std::move(row.run.image);
            row.run.image = Image{};
            say(pair_text(opts.narrow[k]) + " -> " + pair_text(opts.wide) + ": " +
                std::to_string(row.run.counts.queries) + " box tests, " +
                std::to_string(row.run.counts.escalated) + " escalated");
        });
        if (opts.alone)
            tasks.push_back([&, k] {
                res.rows[k].alone =
                    run_fixed(mesh, bvh, opts.render, opts.narrow[k], FixedMode::Conservative, nullptr).figures;
                say(pair_text(opts.narrow[k]) + " alone: " +
                    std::to_string(res.rows[k].alone->stats.traversal.box_tests) + " box tests");
            });
    }
    run_tasks(tasks, res.options.threads);
    for (std::size_t k = 0; k < res.rows.size(); ++k) res.rows[k].wrong_pixels = wrong_pixels(images[k], ref_img);
    res.seconds = seconds();
    return res;
}

nlohmann::json cascade_counts_json(const CascadeCounts& c) {
    nlohmann::json j = {{"queries", c.queries},
                        {"certain_hits", c.certain_hits},
                        {"certain_misses", c.certain_misses},
                        {"escalated", c.escalated},
                        {"escalated_fraction", c.escalated_fraction()},
                        {"wide_hits", c.wide_hits},
                        {"hits", c.hits}};
    if (c.checked)
        j["checked"] = {{"queries", c.checked},
                        {"exact_hits", c.exact_hits},
                        {"false_hits", c.false_hits},
                        {"false_misses", c.false_misses},
                        {"false_certain_hits", c.false_certain_hits}};
    return j;
}

nlohmann::json cascade_study_json(const CascadeStudyResult& r, const Mesh& mesh, const Bvh& bvh, BuildMethod build) {
    const RenderOptions& o = r.options.render;
    const std::uint64_t pixels = static_cast<std::uint64_t>(o.width) * static_cast<std::uint64_t>(o.height);
    nlohmann::json j = run_header_json(mesh, bvh, build, o, r.options.threads, r.seconds);
    j["wide"] = {{"coord_bits", r.options.wide.coord_bits}, {"dir_bits", r.options.wide.dir_bits}};
    j["definitions"] = {
        {"escalated_fraction", "uncertain narrow answers / narrow box queries of the cascade render"},
        {"extra_percent", "100 * (box tests - reference box tests) / reference box tests, all rays of the render"},
        {"reference", "the batched fixed-point traversal with every box query answered by exact_hit (study.hpp)"},
        {"checked", "every cascade answer against exact_hit; false_misses and false_certain_hits must be 0"},
    };
    j["reference"] = work_json(r.reference, nullptr, pixels);
    if (r.wide_alone) j["wide_alone"] = work_json(*r.wide_alone, &r.reference, pixels);
    nlohmann::json rows = nlohmann::json::array();
    for (const CascadeStudyRow& row : r.rows) {
        WorkFigures w;
        w.stats = row.run.stats;
        w.wrong_pixels = row.wrong_pixels;
        nlohmann::json e = {{"coord_bits", row.narrow.coord_bits},
                            {"dir_bits", row.narrow.dir_bits},
                            {"cascade", work_json(w, &r.reference, pixels)},
                            {"answers", cascade_counts_json(row.run.counts)}};
        if (row.alone) e["narrow_alone"] = work_json(*row.alone, &r.reference, pixels);
        rows.push_back(e);
    }
    j["narrow"] = rows;
    return j;
}

}  // namespace pluecker
