// SPDX-License-Identifier: MIT
// The AXI4-Stream wrapper's part of the port contract (rtl/pluecker_axis.sv):
// where each input port of the intersector lies in s_axis_tdata_i.
//
// One query is one beat. Its tdata holds the intersector's payload input
// ports (contract.hpp's port list without clock, reset, handshake and tag:
// ray_class_i, ray_org_i, ray_dir_i, ray_end_i, ray_end_valid_i, box_min_i,
// box_max_i) one after another from bit 0, in port-list order, each with its
// own encoding (x in the low field), and zeros above them up to a whole
// number of bytes (AXI4-Stream's TDATA is bytes). The result beat carries
// the hit in bit 0 of an 8-bit m_axis_tdata_o (and in m_axis_tuser_o); the
// tag travels as tid, the packet end as tlast.
//
// The layout is derived here from the port list, and only here: the RTL
// reads it from functions of the generated package rtl/pluecker_contract_pkg.sv
// (axis_sv_functions), the Python binding and `pluecker contract` from
// axis_tdata_fields.
#pragma once

#include "pluecker/contract.hpp"

#include <string>
#include <vector>

namespace pluecker {

struct TdataField {
    std::string port;  // the intersector's input port
    int lsb = 0;       // its lowest bit in s_axis_tdata_i
    int width = 0;
};

// The payload ports in tdata order, with their offsets.
std::vector<TdataField> axis_tdata_fields(const PortContract& pc);
// The bits of the fields together (QUERY_BITS in the RTL).
int axis_query_bits(const PortContract& pc);
// s_axis_tdata_i's width: axis_query_bits rounded up to a multiple of 8.
int axis_tdata_bits(const PortContract& pc);
// m_axis_tdata_o's width (the hit in bit 0).
inline constexpr int kAxisResultBits = 8;

// One field's width or offset as a linear function of the widths:
// constant + per_coord * COORD_BITS + per_dir * DIR_BITS.
struct WidthTerm {
    int constant = 0, per_coord = 0, per_dir = 0;
    int at(int coord_bits, int dir_bits) const { return constant + per_coord * coord_bits + per_dir * dir_bits; }
    bool operator==(const WidthTerm&) const = default;
};

struct TdataFieldTerm {
    std::string port;
    WidthTerm lsb, width;
};

// The field table with offsets and widths as functions of COORD_BITS and
// DIR_BITS (read off the port list at two probe configurations).
std::vector<TdataFieldTerm> axis_tdata_terms();

// The functions of rtl/pluecker_contract_pkg.sv that give the table to the
// RTL: axis_fields(), axis_field_lsb(k, c, d), axis_field_bits(k, c, d),
// axis_query_bits(c, d), axis_tdata_bits(c, d).
std::string axis_sv_functions();

}  // namespace pluecker
