// SPDX-License-Identifier: MIT
// `pluecker_sim render` of a binary32 unit: the model's batched render path
// on the float BVH with every box query answered by the unit's RTL
// (hardware in the loop), each answer checked against the unit's model.
// Scene, camera and image options are those of `pluecker render`, so the
// image equals `pluecker render --test f32-pluecker|f32-pluecker-cons|f32-smits`
// (the build's unit) with the same options.
#include "float_rtl.hpp"
#include "hil_render.hpp"

#include "pluecker/batched.hpp"

#include <chrono>
#include <cstdio>
#include <optional>
#include <span>
#include <string>
#include <vector>

namespace pluecker::sim {
namespace {

constexpr const char* kUsage =
    "usage: pluecker_sim render [options of 'pluecker render'] [--out IMG.png] [--stats STATS.json]\n"
    "Renders like 'pluecker render --test <the built unit>' (f32-pluecker, f32-pluecker-cons\n"
    "or f32-smits; same options and defaults, see 'pluecker render --help'), through the\n"
    "model's batched traversal of the float BVH with --pool rays in flight; every batch\n"
    "of box queries is streamed back to back through the RTL and each answer is compared\n"
    "with the unit's model (f32unit.hpp).\n"
    "  --out FILE     PNG image                                        [render.png]\n"
    "  --stats FILE   the statistics of 'pluecker render' plus an \"rtl\" section\n"
    "  --quiet        no progress on stderr\n"
    "exit status: 0 ok, 1 mismatch or RTL protocol error, 2 bad input or options\n";

// Mismatches printed in full before the harness only counts them.
constexpr std::uint64_t kMaxReported = 10;

// Answers every batch with the RTL and checks each answer against the model.
class FloatRtlEngine final : public F32BoxEngine<kBuiltTest> {
public:
    explicit FloatRtlEngine(FloatRtl& rtl) : rtl_(&rtl) {}

    void test(std::span<const F32BoxQuery<kBuiltTest>> batch, std::span<std::uint8_t> hits) override {
        const auto t0 = std::chrono::steady_clock::now();
        packed_.resize(batch.size());
        for (std::size_t i = 0; i < batch.size(); ++i) packed_[i] = pack(batch[i].unit);
        rtl_->run(packed_.data(), batch.size(), hits.data());
        rtl_seconds_ += std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
        for (std::size_t i = 0; i < batch.size(); ++i) {
            if ((hits[i] != 0) == model_hit(batch[i].unit)) continue;
            if (++mismatches_ <= kMaxReported) {
                const Query& q = batch[i].query;
                std::fprintf(stderr,
                             "mismatch: batch %llu query %zu (node %u): RTL %d, model %d; query: %a %a %a %a %a %a %a "
                             "%a %a %a %a %a %a\n",
                             static_cast<unsigned long long>(batches_), i, batch[i].node, hits[i] ? 1 : 0,
                             hits[i] ? 0 : 1, double(q.ray.o.x), double(q.ray.o.y), double(q.ray.o.z),
                             double(q.ray.d.x), double(q.ray.d.y), double(q.ray.d.z), double(q.ray.tmax),
                             double(q.box.lo.x), double(q.box.lo.y), double(q.box.lo.z), double(q.box.hi.x),
                             double(q.box.hi.y), double(q.box.hi.z));
            }
        }
        queries_ += batch.size();
        ++batches_;
    }

    std::uint64_t queries() const { return queries_; }
    std::uint64_t mismatches() const { return mismatches_; }
    std::uint64_t batches() const { return batches_; }
    double rtl_seconds() const { return rtl_seconds_; }

private:
    FloatRtl* rtl_;
    std::vector<PackedQuery> packed_;
    std::uint64_t queries_ = 0;
    std::uint64_t mismatches_ = 0;
    std::uint64_t batches_ = 0;
    double rtl_seconds_ = 0;
};

}  // namespace

int cmd_render(const std::vector<std::string>& argv) {
    // The unit has no build options a render could contradict but its test.
    const std::optional<app::Args> a = render_args(argv, kUsage, test_name(kBuiltTest), [](const app::Args&) {}, {});
    if (!a) return 0;
    const auto s = batched_setup(*a);

    FloatRtl rtl;
    FloatRtlEngine engine(rtl);
    RenderStats st;
    const StreamStats& rs = rtl.stats();
    auto qps = [&] {
        return engine.rtl_seconds() > 0 ? static_cast<double>(engine.queries()) / engine.rtl_seconds() : 0.0;
    };
    const double seconds = render_through(*s, *a, engine, st, [&](double wall) {
        nlohmann::json j = rtl_section("pluecker_sim", engine.queries(), engine.batches(), engine.mismatches(),
                                       engine.rtl_seconds(), rs, wall);
        j["unit"] = build_name();
        return j;
    });
    std::printf("render %s %dx%d (%s, order %s, build %s): %llu box queries in %llu batches through the RTL, "
                "%llu cycles, %.3f M queries/s in the RTL loop, %.2f s in all, %llu mismatches\n",
                s->mesh.name.c_str(), s->opts.width, s->opts.height, build_name().c_str(), order_name(s->opts.order),
                method_name(s->build), static_cast<unsigned long long>(engine.queries()),
                static_cast<unsigned long long>(engine.batches()), static_cast<unsigned long long>(rs.cycles),
                qps() / 1e6, seconds, static_cast<unsigned long long>(engine.mismatches()));
    return engine.mismatches() == 0 ? 0 : 1;
}

}  // namespace pluecker::sim
