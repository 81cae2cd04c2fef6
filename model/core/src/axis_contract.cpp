// SPDX-License-Identifier: MIT
// Offsets of the intersector's input ports in the AXI4-Stream wrapper's
// tdata (axis_contract.hpp).
#include "pluecker/axis_contract.hpp"


#include <sstream>
#include <string_view>

namespace pluecker {

namespace {

// Inputs that are handshake, clock, reset or tag travel outside tdata.
bool in_tdata(const PortSpec& p) {
    if (p.dir != PortDir::In) return false;
    for (std::string_view other : {"clk_i", "rst_i", "in_valid_i", "in_tag_i", "out_ready_i"})
        if (p.name == other) return false;
    return true;
}

PortContract probe(int coord_bits, int dir_bits) {
    RtlConfig c;
    c.coord_bits = coord_bits;
    c.dir_bits = dir_bits;
    return PortContract(c);
}

// A term from its values at (C0, D0), (C0 + 1, D0) and (C0, D0 + 1).
WidthTerm term_of(int v00, int v10, int v01, int c0, int d0) {
    WidthTerm t;
    t.per_coord = v10 - v00;
    t.per_dir = v01 - v00;
    t.constant = v00 - t.per_coord * c0 - t.per_dir * d0;
    return t;
}

std::string sv_expr(const WidthTerm& t) {
    std::ostringstream s;
    const char* sep = "";
    if (t.constant != 0 || (t.per_coord == 0 && t.per_dir == 0)) {
        s << t.constant;
        sep = " + ";
    }
    if (t.per_coord != 0) {
        s << sep << t.per_coord << " * c";
        sep = " + ";
    }
    if (t.per_dir != 0) s << sep << t.per_dir << " * d";
    return s.str();
}

}  // namespace

std::vector<TdataField> axis_tdata_fields(const PortContract& pc) {
    std::vector<TdataField> out;
    int lsb = 0;
    for (const PortSpec& p : pc.ports()) {
        if (!in_tdata(p)) continue;
        out.push_back({p.name, lsb, p.width()});
        lsb += p.width();
    }
    return out;
}

int axis_query_bits(const PortContract& pc) {
    const auto f = axis_tdata_fields(pc);
    return f.back().lsb + f.back().width;
}

int axis_tdata_bits(const PortContract& pc) { return (axis_query_bits(pc) + 7) / 8 * 8; }

std::vector<TdataFieldTerm> axis_tdata_terms() {
    const int c0 = ContractLimits::kMinBits, d0 = ContractLimits::kMinBits;
    const auto f00 = axis_tdata_fields(probe(c0, d0));
    const auto f10 = axis_tdata_fields(probe(c0 + 1, d0));
    const auto f01 = axis_tdata_fields(probe(c0, d0 + 1));
    std::vector<TdataFieldTerm> out;
    for (std::size_t k = 0; k < f00.size(); ++k)
        out.push_back({f00[k].port, term_of(f00[k].lsb, f10[k].lsb, f01[k].lsb, c0, d0),
                       term_of(f00[k].width, f10[k].width, f01[k].width, c0, d0)});
    return out;
}

std::string axis_sv_functions() {
    const auto terms = axis_tdata_terms();
    const TdataFieldTerm& last = terms.back();
    const WidthTerm query{last.lsb.constant + last.width.constant, last.lsb.per_coord + last.width.per_coord,
                          last.lsb.per_dir + last.width.per_dir};
    std::ostringstream s;
    s << "\n"
         "  // The AXI4-Stream wrapper (pluecker_axis): s_axis_tdata_i holds the\n"
         "  // intersector's payload input ports back to back from bit 0, field k\n"
         "  // (0..axis_fields() - 1) at axis_field_lsb(k, c, d), axis_field_bits(k, c, d)\n"
         "  // wide (c = COORD_BITS, d = DIR_BITS), zeros above axis_query_bits(c, d)\n"
         "  // up to axis_tdata_bits(c, d), a whole number of bytes.\n"
         "  function automatic int axis_fields();\n"
         "    axis_fields = " << terms.size() << ";\n"
         "  endfunction\n";
    for (const char* what : {"lsb", "bits"}) {
        const bool lsb = std::string_view(what) == "lsb";
        s << "  function automatic int axis_field_" << what << "(input int k, input int c, input int d);\n"
          << "    case (k)\n";
        for (std::size_t k = 0; k < terms.size(); ++k)
            s << "      " << k << ": axis_field_" << what << " = " << sv_expr(lsb ? terms[k].lsb : terms[k].width)
              << ";  // " << terms[k].port << "\n";
        s << "      default: axis_field_" << what << " = -1;\n"
          << "    endcase\n"
          << "  endfunction\n";
    }
    s << "  function automatic int axis_query_bits(input int c, input int d);\n"
         "    axis_query_bits = " << sv_expr(query) << ";\n"
         "  endfunction\n"
         "  function automatic int axis_tdata_bits(input int c, input int d);\n"
         "    axis_tdata_bits = (axis_query_bits(c, d) + 7) / 8 * 8;\n"
         "  endfunction\n";
    return s.str();
}

}  // namespace pluecker
