# SPDX-License-Identifier: MIT
"""The pytest side of the binary32 units' benches: one Verilator build per
parameter set (pluecker_tb.runner), on the generic multiplier path or with
PLUECKER_ECP5 and the MULT18X18D model (pluecker_tb.ecp5), and the run of
the cocotb tests of the bench module."""

from __future__ import annotations


def build_and_test(toplevel: str, test_module: str, name: str, parameters: dict, ecp5: bool,
                   queries: float) -> None:
    from pluecker_tb import config, ecp5 as e5
    from pluecker_tb.runner import VERILATOR_RTL_ARGS, Build, rtl_sources, verilator_plusargs

    sources, defines = rtl_sources(), {"ASSERT_ON": 1}
    if ecp5:
        sources += e5.model_sources()
        defines["PLUECKER_ECP5"] = 1
    build = Build(f"{toplevel}_{name}").build(sources=sources, hdl_toplevel=toplevel, parameters=parameters,
                                               defines=defines, build_args=VERILATOR_RTL_ARGS)
    if ecp5:
        # pluecker_mul's MULT18X18D instances, as a module of their own or
        # inlined (signals named u_mult__...).
        assert (any(build.dir.glob("Vtop_MULT18X18D*.h"))
                or any(b"u_mult__" in h.read_bytes() for h in build.dir.glob("Vtop*.h"))), \
            "the build has no MULT18X18D: not the DSP path"
    build.test(test_module, plusargs=verilator_plusargs(config.seed(toplevel, name)),
               extra_env={"PLUECKER_TB_QUERIES": str(queries)})
