# SPDX-License-Identifier: MIT
"""The port contract through the binding (pluecker_py.PortContract) against
the generated table the scripts read (rtl/pluecker_contract.json through
scripts/contract.py): the same limits and, for every configuration, the
same row. With the C++ test Contract.GeneratedFilesAreCurrent (the table is
what the C++ contract generates) and the RTL's elaboration check (it derives
what the package says), a divergence of any layer fails a test.
"""

from __future__ import annotations

import random
import sys
from pathlib import Path

import pytest

pp = pytest.importorskip("pluecker_py")

REPO = Path(__file__).resolve().parents[2]
sys.path.insert(0, str(REPO / "scripts"))
import contract  # noqa: E402  (scripts/contract.py)

STYLES = ("auto", "dsp", "lut", "rom")


def test_limits_agree():
    lo, hi = contract.limits()
    assert (pp.PortContract.MIN_BITS, pp.PortContract.MAX_BITS) == (lo, hi)
    assert (pp.FixedFormat.MIN_BITS, pp.FixedFormat.MAX_BITS) == (lo, hi)
    lim = contract.load()["limits"]
    assert pp.PortContract.MIN_TAG_BITS == lim["tag_bits_min"]
    assert [0, pp.PortContract.MAX_PIPELINE] == lim["pipeline"]
    d = contract.defaults()
    c = pp.PortContract()
    assert (c.coord_bits, c.dir_bits, c.tag_bits, int(c.conservative), pp.mul_style_name(c.mul_style),
            c.pipeline) == (d["coord_bits"], d["dir_bits"], d["tag_bits"], d["conservative"], d["mul_style"],
                            d["pipeline"])


def test_classes_agree():
    table = contract.classes()
    binding = pp.contract_classes()
    assert len(table) == len(binding)
    for t, b in zip(table, binding):
        assert {k: (list(v) if isinstance(v, tuple) else v) for k, v in b.items()} == t


def test_every_configuration_has_the_row_of_the_table():
    lo, hi = contract.limits()
    n = 0
    for c in range(lo, hi + 1):
        for d in range(lo, hi + 1):
            for style in STYLES:
                for p in (0, 1, 2):
                    try:
                        row = contract.row(c, d, style, p)
                    except contract.ContractError:
                        with pytest.raises(pp.InputError):
                            pp.PortContract(c, d, mul_style=style, pipeline=p)
                        continue
                    pc = pp.PortContract(c, d, mul_style=style, pipeline=p)
                    kind = "rom" if pc.rom_multipliers else "lut" if pc.fabric_multipliers else "dsp"
                    got = (kind, pc.mul_add, pc.s2x_stages, pc.latency, pc.fifo_depth, pc.dsp_blocks, pc.rom_blocks)
                    assert got == tuple(row[k] for k in contract.ROW_KEYS), (c, d, style, p)
                    n += 1
    # auto, dsp: every pair; lut: up to 17 bits; rom: 6/6 at PIPELINE 2.
    assert n == 3 * (19 * 19 * 2 + 12 * 12) + 1


@pytest.mark.parametrize("kwargs, part", [
    ({"coord_bits": 5}, "COORD_BITS = 5"),
    ({"dir_bits": 25}, "DIR_BITS = 25"),
    ({"tag_bits": 0}, "TAG_BITS = 0"),
    ({"pipeline": 3}, "PIPELINE = 3"),
    ({"mul_style": "fast"}, "fast"),
    ({"coord_bits": 18, "mul_style": "lut"}, "MUL_STYLE lut"),
    ({"coord_bits": 6, "dir_bits": 6, "mul_style": "rom", "pipeline": 1}, "MUL_STYLE rom needs PIPELINE = 2"),
    ({"coord_bits": 6, "dir_bits": 8, "mul_style": "rom", "pipeline": 2}, "one 1K x 18 block-RAM port"),
])
def test_contract_refuses(kwargs, part):
    with pytest.raises(pp.InputError, match=part):
        pp.PortContract(**kwargs)


def test_rtl_ports_is_the_contract_encoding():
    """x in the low field, two's complement coordinates, field widths and
    offsets as PortContract.ports states them."""
    rng = random.Random(3)
    for c, d in ((6, 6), (11, 17), (24, 24)):
        pc = pp.PortContract(c, d)
        f = pc.format
        for _ in range(50):
            org = [rng.randint(f.coord_min(), f.coord_max()) for _ in range(3)]
            end = [rng.randint(f.coord_min(), f.coord_max()) for _ in range(3)]
            lo = [rng.randint(f.coord_min(), f.coord_max()) for _ in range(3)]
            hi = [rng.randint(f.coord_min(), f.coord_max()) for _ in range(3)]
            dr = [rng.randint(0, 2**d - 1) for _ in range(3)]
            r = pp.FixedRay(rng.randint(0, 7), org, dr, end, bool(rng.getrandbits(1)))
            b = pp.FixedBox(lo, hi)
            ports = pc.rtl_ports(r, b)
            assert ports == pp.rtl_ports(r, b, f)
            for name, values in (("ray_org_i", org), ("ray_dir_i", dr), ("ray_end_i", end), ("box_min_i", lo),
                                 ("box_max_i", hi)):
                spec = pc.port(name)
                for axis, v in enumerate(values):
                    field = (ports[name] >> spec.field_lsb(axis)) & ((1 << spec.field_bits) - 1)
                    assert field == v % (1 << spec.field_bits), (name, axis)
                assert ports[name] < 1 << spec.width
            assert ports["ray_class_i"] == r.cls
            assert ports["ray_end_valid_i"] == int(r.has_end)
