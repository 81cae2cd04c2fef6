# SPDX-License-Identifier: MIT
"""Traffic generators: when the driver leaves the input idle, and when the
sink refuses a result (backpressure). Each is asked once per clock.

  NoIdle / AlwaysReady   full rate
  IdleGaps               short random gaps (35 %) and now and then a long
                         pause (5..40 cycles)
  Backpressure           random stalls (40 %) and now and then a long one
                         (5..60 cycles: long enough to fill the FIFO)
  Phases                 both at once, in named phases that the stress bench
                         switches between (full, bursty, sparse, jitter,
                         trickle, stall of 100..800 cycles)

A sink's ready can be forced with `override` (e.g. held low to block the
output on purpose); None gives the generator back its say.
"""

from __future__ import annotations

import random


class NoIdle:
    def idle_now(self) -> bool:
        return False


class AlwaysReady:
    override: int | None = None

    def ready_now(self) -> int:
        return 1 if self.override is None else self.override


class IdleGaps(NoIdle):
    def __init__(self, rng: random.Random, p_idle: float = 0.35, p_pause: float = 0.02, pause=(5, 40)):
        self.rng, self.p_idle, self.p_pause, self.pause = rng, p_idle, p_pause, pause
        self._gap = 0

    def idle_now(self) -> bool:
        if self._gap > 0:
            self._gap -= 1
            return True
        if self.rng.random() < self.p_pause:
            self._gap = self.rng.randint(*self.pause)
            return True
        return self.rng.random() < self.p_idle


class Backpressure(AlwaysReady):
    def __init__(self, rng: random.Random, p_stall: float = 0.4, p_long: float = 0.03, stall=(5, 60)):
        self.rng, self.p_stall, self.p_long, self.stall = rng, p_stall, p_long, stall
        self.override = None
        self._stall = 0

    def ready_now(self) -> int:
        if self.override is not None:
            return self.override
        if self._stall > 0:
            self._stall -= 1
            return 0
        if self.rng.random() < self.p_long:
            self._stall = self.rng.randint(*self.stall)
            return 0
        return int(self.rng.random() >= self.p_stall)


def idle_generator(rng: random.Random, idle: bool):
    return IdleGaps(rng) if idle else NoIdle()


def ready_generator(rng: random.Random, backpressure: bool):
    return Backpressure(rng) if backpressure else AlwaysReady()


class Phases(AlwaysReady):
    """Idle and ready together, by phase (the stress bench's traffic)."""

    MODES = ["full", "bursty", "sparse", "jitter", "trickle", "stall"]

    def __init__(self, rng: random.Random):
        self.rng = rng
        self.mode = "full"
        self.override = None
        self._gap = 0
        self._stall_left = 0

    def set_mode(self, mode: str) -> None:
        self.mode = mode
        if mode == "stall":
            self._stall_left = self.rng.randint(100, 800)

    def idle_now(self) -> bool:
        m, r = self.mode, self.rng.random()
        if m in ("full", "stall"):
            return False
        if m == "bursty":
            if self._gap > 0:
                self._gap -= 1
                return True
            if r < 0.1:
                self._gap = self.rng.randint(1, 30)
                return True
            return False
        if m == "sparse":
            return r < 0.1
        if m == "trickle":
            return r >= 0.05
        return r < 0.5  # jitter

    def ready_now(self) -> int:
        if self.override is not None:
            return self.override
        m = self.mode
        if m == "stall":
            if self._stall_left > 0:
                self._stall_left -= 1
                return 0
            self.mode = "full"
            return 1
        if m == "sparse":
            return int(self.rng.random() < 0.1)
        if m == "jitter":
            return int(self.rng.random() < 0.5)
        return 1
