# SPDX-License-Identifier: MIT
"""Hostile input through the Python binding `pluecker_py` (model/python/binding.cpp).

Every bad argument must raise pluecker_py.InputError (a ValueError) naming
the field, never reach the C++ model as undefined behaviour (a width outside
6..24 would shift by a negative or too large count) and never change the
object it was refused for. The binding is found through PLUECKER_PY_DIR
(tb/conftest.py; default build/model).
"""

from __future__ import annotations

import math

import pytest

try:
    import pluecker_py as pp
except ImportError as e:  # a missing model build fails the run, never skips it
    raise ImportError(f"pluecker_py not found (PLUECKER_PY_DIR; `make build` builds it): {e}") from e

NAN = math.nan
INF = math.inf
LO, HI = 6, 24  # FixedFormat.MIN_BITS, MAX_BITS


def test_width_limits_are_exported():
    assert (pp.FixedFormat.MIN_BITS, pp.FixedFormat.MAX_BITS) == (LO, HI)
    assert issubclass(pp.InputError, ValueError)


@pytest.mark.parametrize("field", ["coord_bits", "dir_bits"])
@pytest.mark.parametrize("bits", [LO - 1, HI + 1, 0, -1, -2**31, 63, 64, 1000, 2**31 - 1])
def test_width_setter_rejects_and_keeps_value(field, bits):
    f = pp.FixedFormat(12, 10)
    before = (f.coord_bits, f.dir_bits)
    with pytest.raises(pp.InputError) as e:
        setattr(f, field, bits)
    msg = str(e.value)
    assert f"FixedFormat.{field} = {bits}" in msg
    assert f"{LO}..{HI}" in msg
    assert (f.coord_bits, f.dir_bits) == before
    f.validate()  # still a valid format


@pytest.mark.parametrize("field", ["coord_bits", "dir_bits"])
def test_width_setter_accepts_the_whole_range(field):
    f = pp.FixedFormat()
    for bits in range(LO, HI + 1):
        setattr(f, field, bits)
        assert getattr(f, field) == bits
        f.validate()


@pytest.mark.parametrize("field", ["coord_bits", "dir_bits"])
@pytest.mark.parametrize("value", [2**40, -2**40, 12.5, "12", None])
def test_width_setter_rejects_non_ints(field, value):
    # Not an int of C++ size: pybind11 refuses it before the setter runs.
    f = pp.FixedFormat()
    with pytest.raises((TypeError, ValueError)):
        setattr(f, field, value)
    assert (f.coord_bits, f.dir_bits) == (16, 16)


@pytest.mark.parametrize("kwargs, name", [
    ({"coord_bits": LO - 1}, "COORD_BITS"),
    ({"coord_bits": HI + 1}, "COORD_BITS"),
    ({"dir_bits": LO - 1}, "DIR_BITS"),
    ({"dir_bits": 99}, "DIR_BITS"),
])
def test_constructor_rejects_bad_widths(kwargs, name):
    with pytest.raises(pp.InputError, match=name):
        pp.FixedFormat(**kwargs)


def test_bad_mode():
    with pytest.raises(pp.InputError, match="fuzzy"):
        pp.FixedFormat(mode="fuzzy")
    with pytest.raises(pp.InputError, match="mode"):
        pp.FixedFormat(mode=3)


def unit_box():
    return pp.Box((0.0, 0.0, 0.0), (1.0, 1.0, 1.0))


FLOAT_TESTS = ["exact_hit", "smits_hit", "pluecker_hit"]


@pytest.mark.parametrize("test", FLOAT_TESTS)
@pytest.mark.parametrize("o, d, tmax, box, part", [
    ((NAN, 0.5, -1.0), (0.0, 0.0, 1.0), INF, None, "ox is NaN"),
    ((0.5, 0.5, -1.0), (0.0, NAN, 1.0), INF, None, "dy is NaN"),
    ((0.5, 0.5, -1.0), (0.0, 0.0, 1.0), NAN, None, "tmax is NaN"),
    ((0.5, 0.5, -1.0), (0.0, 0.0, 1.0), INF, ((0.0, 0.0, 0.0), (1.0, 1.0, NAN)), "maxz is NaN"),
    ((0.5, 0.5, -1.0), (0.0, 0.0, 0.0), INF, None, "direction is zero"),
    ((0.5, 0.5, -1.0), (-0.0, 0.0, -0.0), INF, None, "direction is zero"),
    ((0.5, 0.5, -1.0), (0.0, 0.0, INF), INF, None, "dz is not a finite direction component"),
    ((0.5, INF, -1.0), (0.0, 0.0, 1.0), INF, None, "oy is not a finite coordinate"),
    ((0.5, 0.5, -1.0), (0.0, 0.0, 1.0), -0.5, None, "tmax is negative"),
    ((0.5, 0.5, -1.0), (0.0, 0.0, 1.0), INF, ((2.0, 0.0, 0.0), (1.0, 1.0, 1.0)), "box min > max on axis x"),
])
def test_float_tests_reject_bad_queries(test, o, d, tmax, box, part):
    ray = pp.Ray(o, d, tmax)
    b = pp.Box(*box) if box else unit_box()
    fn = getattr(pp, test)
    with pytest.raises(pp.InputError, match=part.replace("(", r"\(")):
        fn(ray, b)
    with pytest.raises(pp.InputError, match=part.replace("(", r"\(")):
        fn(pp.Query(ray, b))


@pytest.mark.parametrize("d", [(0.0, 0.0, 0.0), (NAN, 0.0, 1.0), (0.0, INF, 1.0)])
def test_fixed_setup_rejects_zero_nan_inf_direction(d):
    f = pp.FixedFormat()
    ray = pp.Ray((0.5, 0.5, -1.0), d)
    with pytest.raises(pp.InputError, match="ray direction"):
        pp.fixed_setup_ray(ray, f)
    with pytest.raises(pp.InputError, match="ray direction"):
        pp.fixed_hit(ray, unit_box(), f)


@pytest.mark.parametrize("lo, hi", [
    ((NAN, 0.0, 0.0), (1.0, 1.0, 1.0)),
    ((0.0, 0.0, 0.0), (INF, 1.0, 1.0)),
    ((1.0, 0.0, 0.0), (0.0, 1.0, 1.0)),
])
def test_fixed_quantize_rejects_bad_boxes(lo, hi):
    with pytest.raises(pp.InputError, match="box x extent"):
        pp.fixed_quantize_box(pp.Box(lo, hi), pp.FixedFormat())


def test_fixed_quantize_rejects_out_of_range_box():
    with pytest.raises(pp.InputError, match=r"outside the fixed-point range \[-2, 1.99993896\] of COORD_BITS = 16"):
        pp.fixed_quantize_box(pp.Box((0.0, 0.0, 0.0), (2.0, 1.0, 1.0)), pp.FixedFormat())
    f6 = pp.FixedFormat(6, 6)
    assert f6.range_text() == "[-2, 1.9375] of COORD_BITS = 6"
    assert (f6.coord_lo_value(), f6.coord_hi_value()) == (-2.0, 1.9375)
    pp.fixed_quantize_box(pp.Box((-2.0, -2.0, -2.0), (1.9375, 1.9375, 1.9375)), f6)  # the range's own corners
    with pytest.raises(pp.InputError, match=r"box x extent \[0, 1.93750012\] is outside the fixed-point range \[-2, 1.9375\] of COORD_BITS = 6"):
        pp.fixed_quantize_box(pp.Box((0.0, 0.0, 0.0), (float.fromhex("0x1.f00002p+0"), 1.0, 1.0)), f6)


@pytest.mark.parametrize("o", [(INF, 0.0, 0.0), (0.0, NAN, 0.0), (0.0, 0.0, -INF)])
def test_fixed_setup_rejects_nonfinite_origin(o):
    with pytest.raises(pp.InputError, match="ray origin . = .* is not finite"):
        pp.fixed_setup_ray(pp.Ray(o, (0.0, 0.0, 1.0)), pp.FixedFormat())


def test_fixed_setup_takes_any_finite_origin():
    """A camera 1e6 away is clipped onto the range cube; a ray that never
    meets the cube is None (a miss without an RTL query)."""
    f = pp.FixedFormat(24, 24)
    box = pp.Box((-0.25, -0.25, -0.25), (0.25, 0.25, 0.25))
    towards = pp.Ray((0.0, 0.0, -1e6), (0.0, 0.0, 1.0))
    r = pp.fixed_setup_ray(towards, f)
    assert r is not None and r.clipped
    assert r.org[2] == f.coord_min() and r.org[0] == r.org[1] == 0
    assert pp.fixed_hit(towards, box, f) and pp.exact_hit(towards, box)
    away = pp.Ray((0.0, 0.0, -1e6), (0.0, 0.0, -1.0))
    assert pp.fixed_setup_ray(away, f) is None
    assert not pp.fixed_hit(away, box, f)
    # A segment that ends before the range: also a miss.
    short = pp.Ray((0.0, 0.0, -1e6), (0.0, 0.0, 1.0), 1000.0)
    assert pp.fixed_setup_ray(short, f) is None
    # fixed_setup_end shortens the same ray: the origin stays, the end moves.
    inside = pp.Ray((0.0, 0.0, -1.0), (0.0, 0.0, 1.0))
    full = pp.fixed_setup_ray(inside, f)
    ends = pp.fixed_setup_end(full, pp.Ray((0.0, 0.0, -1.0), (0.0, 0.0, 1.0), 0.5), f)
    assert ends.has_end and ends.org == full.org and not full.has_end
    assert ends.end[2] == -(1 << 21)  # -0.5 * 2^22


def test_fixed_operands_checked_against_the_format():
    f = pp.FixedFormat(8, 8)
    ok_ray = pp.FixedRay(cls=0, org=(0, 0, 0), dir=(1, 1, 1))
    ok_box = pp.FixedBox((0, 0, 0), (1, 1, 1))
    assert pp.fixed_hit(ok_ray, ok_box, f) in (True, False)
    with pytest.raises(pp.InputError, match="does not fit COORD_BITS = 8"):
        pp.fixed_hit(pp.FixedRay(org=(128, 0, 0), dir=(1, 1, 1)), ok_box, f)
    with pytest.raises(pp.InputError, match="does not fit DIR_BITS = 8"):
        pp.fixed_hit(pp.FixedRay(org=(0, 0, 0), dir=(256, 1, 1)), ok_box, f)
    with pytest.raises(pp.InputError, match="does not fit"):
        pp.rtl_ports(ok_ray, pp.FixedBox((0, 0, 0), (1, 1, -200)), f)
    for cls in (-1, 8):
        with pytest.raises(pp.InputError, match="outside 0..7"):
            pp.FixedRay(cls=cls)
        with pytest.raises(pp.InputError, match="outside 0..7"):
            pp.class_name(cls)
    r = pp.FixedRay()
    with pytest.raises(pp.InputError, match="outside 0..7"):
        r.cls = 9
    assert r.cls == 0


def test_query_text_names_line_and_field():
    good = "0.5 0.5 -1 0 0 1 inf 0 0 0 1 1 1\n"
    with pytest.raises(pp.InputError, match=r"^t\.txt:2: dx is NaN"):
        pp.read_queries_text(good + "0.5 0.5 -1 nan 0 1 inf 0 0 0 1 1 1\n", "t.txt")
    with pytest.raises(pp.InputError, match=r"^t\.txt:2: direction is zero"):
        pp.read_queries_text(good + "0.5 0.5 -1 0 0 0 inf 0 0 0 1 1 1\n", "t.txt")
    with pytest.raises(pp.InputError, match=r"^t\.txt:2: field 13 \(maxz\): cannot parse '1\\0x'"):
        pp.read_queries_text(good + "0.5 0.5 -1 0 0 1 inf 0 0 0 1 1 1\0x\n", "t.txt")
    assert len(pp.read_queries_text(good * 3, "t.txt")) == 3
