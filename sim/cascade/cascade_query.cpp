// SPDX-License-Identifier: MIT
// One float query as the cascade takes it (cascade_query.hpp).
#include "cascade_query.hpp"

namespace pluecker::sim {

std::optional<CascadeItem> setup_query(const Ray& ray, const FixedBox& narrow_box, const FixedBox& wide_box,
                                       const CascadeFormats& f) {
    const std::optional<FixedRay> nr = fixed_setup_ray(ray, f.narrow);
    const std::optional<FixedRay> wr = fixed_setup_ray(ray, f.wide);
    if (!nr || !wr) return std::nullopt;
    CascadeItem item;
    item.ports.narrow = pack_query(*nr, narrow_box, f.narrow);
    item.ports.wide = pack_query(*wr, wide_box, f.wide);
    item.model = cascade_answer(*nr, narrow_box, *wr, wide_box, f);
    return item;
}

std::optional<CascadeItem> setup_query(const Ray& ray, const Box& box, const CascadeFormats& f) {
    return setup_query(ray, fixed_quantize_box(box, f.narrow), fixed_quantize_box(box, f.wide), f);
}

const char* disagreement(const CascadeAnswer& model, bool hit, AnswerPath path) {
    switch (path) {
        case AnswerPath::Lane:
            if (model.escalated()) return "a certain answer where the model is uncertain";
            return hit == (model.narrow == TernaryAnswer::Hit) ? nullptr : "a certain answer not the model's";
        case AnswerPath::Escalated:
            if (!model.escalated()) return "escalated where the model is certain";
            return hit == model.hit ? nullptr : "a wide answer not the model's";
        case AnswerPath::None: break;
    }
    return "no answer";
}

CascadeAnswer rtl_answer(bool hit, AnswerPath path) {
    CascadeAnswer a;
    a.hit = hit;
    a.narrow = path == AnswerPath::Escalated ? TernaryAnswer::Uncertain
               : hit                         ? TernaryAnswer::Hit
                                             : TernaryAnswer::Miss;
    return a;
}

}  // namespace pluecker::sim
