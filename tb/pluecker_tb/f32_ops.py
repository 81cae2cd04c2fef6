# SPDX-License-Identifier: MIT
"""The bench of the binary32 primitives pluecker_f32_add and pluecker_f32_mul
(cocotb side): a new operand pair every clock, each result compared with the
golden model (pluecker_py.f32_add / f32_sub / f32_mul, the C++ of
f32unit.hpp) exactly LATENCY edges later, LATENCY being the module's
documented latency, which must equal the port contract's (ADD_LATENCY,
MUL_LATENCY). The primitives are datapaths without valid bits or reset:
every cycle carries an operation, so there are no idle or backpressure
generators to cross.

Operand sets: every pair of a list of special patterns (zeros, subnormals,
2^-126 and its neighbours, 1 and its neighbours, FLT_MAX, infinities,
NaNs); random patterns over every exponent; pairs a few ulps apart
(cancellation, ties); operands around 2^-126 (the flushing paths).
"""

from __future__ import annotations

import random
from collections import deque
from typing import Callable

import cocotb
from cocotb.clock import Clock
from cocotb.triggers import FallingEdge, ReadOnly, RisingEdge

from .float_units import SPECIALS

ROUND_NAMES = {0: "nearest", 1: "up", 2: "down"}


def _random(rng: random.Random) -> int:
    r = rng.random()
    if r < 0.5:
        return (rng.getrandbits(1) << 31) | (rng.randint(100, 150) << 23) | rng.getrandbits(23)
    if r < 0.65:
        return (rng.getrandbits(1) << 31) | (rng.randint(0, 6) << 23) | rng.getrandbits(23)
    if r < 0.75:
        return (rng.getrandbits(1) << 31) | (rng.randint(248, 254) << 23) | rng.getrandbits(23)
    return rng.getrandbits(32)


def operand_pairs(rng: random.Random, n_random: int) -> list[tuple[int, int]]:
    specials = SPECIALS + [x ^ 0x80000000 for x in SPECIALS] + [0x3f800001, 0x3fffffff, 0x4b000000, 0x33800000]
    pairs = [(a, b) for a in specials for b in specials]
    for _ in range(n_random):
        a = _random(rng)
        r = rng.random()
        if r < 0.35:  # a few ulps away, maybe the other sign
            b = (a + rng.randint(-3, 3)) & 0xffffffff
            b ^= 0x80000000 * rng.getrandbits(1)
        elif r < 0.45:  # the same exponent, a random significand
            b = (a & 0xff800000) | rng.getrandbits(23)
        else:
            b = _random(rng)
        pairs.append((a, b))
    rng.shuffle(pairs)
    return pairs


async def run_pairs(dut, out, pairs: list[tuple[int, int]], model: Callable[[int, int], int],
                    contract_latency: int, what: str) -> None:
    """Drives a_i, b_i with one pair per clock and checks `out` LATENCY edges
    later against model(a, b)."""
    latency = int(dut.LATENCY.value)
    assert latency == contract_latency, f"LATENCY {latency}, port contract {contract_latency}"
    Clock(dut.clk_i, 10, unit="ns").start()
    pending: deque = deque()
    errors: list[str] = []
    checked = 0
    for k in range(len(pairs) + latency - 1):
        await FallingEdge(dut.clk_i)
        if k < len(pairs):
            a, b = pairs[k]
            dut.a_i.value = a
            dut.b_i.value = b
            pending.append((a, b, model(a, b)))
        await RisingEdge(dut.clk_i)
        await ReadOnly()
        if k + 1 >= latency:
            a, b, want = pending.popleft()
            got = int(out.value)
            checked += 1
            if got != want and len(errors) < 10:
                errors.append(f"{what}: a=0x{a:08x} b=0x{b:08x}: RTL 0x{got:08x}, model 0x{want:08x}")
                dut._log.error("%s", errors[-1])
    assert not errors, f"{len(errors)}+ mismatches, first: {errors[0]}"
    assert checked == len(pairs)
    dut._log.info("%s: %d results identical to the model after LATENCY %d", what, checked, latency)
