// SPDX-License-Identifier: MIT
// One float query as the cascade takes it, and the model's verdict on the
// cascade's answer. Every value comes from the golden model: the set-up of
// each format (fixed_setup_ray, fixed_quantize_box), the port encoding
// (pack_query) and the expected answer (cascade_answer, ternary.hpp).
#pragma once

#include "cascade_rtl.hpp"

#include "pluecker/fixed.hpp"
#include "pluecker/geometry.hpp"
#include "pluecker/ternary.hpp"

#include <optional>

namespace pluecker::sim {

// A query set up in both formats with the model's answer to it.
struct CascadeItem {
    CascadeQuery ports;
    CascadeAnswer model;
};

// The float ray set up in each format of `f` against that format's
// quantised box. nullopt when the ray never meets either format's range
// cube: the query is then a miss without an RTL query, as
// CascadeBoxEngine (pluecker/cascade.hpp) answers it.
std::optional<CascadeItem> setup_query(const Ray& ray, const FixedBox& narrow_box, const FixedBox& wide_box,
                                       const CascadeFormats& f);
// The same with the float box quantised in each format here.
std::optional<CascadeItem> setup_query(const Ray& ray, const Box& box, const CascadeFormats& f);

// Why the cascade's answer (`hit`, on stream `path`) is not the model's,
// or nullptr when it is: a certain answer must be the narrow answer of a
// query the model is sure about, an escalated one the wide test of a query
// the model finds uncertain.
const char* disagreement(const CascadeAnswer& model, bool hit, AnswerPath path);

// The model's form of the cascade's answer: an escalated answer is an
// uncertain narrow one, a certain one the narrow hit or miss.
CascadeAnswer rtl_answer(bool hit, AnswerPath path);

}  // namespace pluecker::sim
