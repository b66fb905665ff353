"""What the bench's runs of the AXI top share: the fast engine's generics and builds,
the STATUS error bits, and BenchError, raised for any result the bench must not publish."""

from __future__ import annotations

from collections.abc import Callable
from concurrent.futures import ThreadPoolExecutor

import numpy as np
from fastnms.sim import regs, verilator
from fastnms.sim.run import generics_for

STATUS_ERRORS = ["EOL_EARLY", "EOL_LATE", "SOF_MISSING", "SOF_EARLY", "OVERFLOW"]


class BenchError(Exception):
    """A result the bench must not publish: records unlike the golden model's,
    STATUS errors, or two engines that disagree."""


def bench_generics(score: str, nms: str, max_width: int, max_height: int) -> dict[str, object]:
    return {**generics_for(score, nms), "MAX_WIDTH": max_width, "MAX_HEIGHT": max_height}


def build_engines(
    generics: list[dict[str, object]], jobs: int, announce: Callable[[str], None] | None = None
) -> list[float | None]:
    """Build the fast engine for every generic set, `jobs` at a time (each build
    runs GHDL, Verilator and g++ in subprocesses, so threads are enough); each
    one's build seconds, None when it was already built."""
    try:
        with ThreadPoolExecutor(max_workers=max(1, jobs)) as pool:
            return list(pool.map(lambda g: verilator.build(g, announce)[1], generics))
    except verilator.EngineError as e:
        raise BenchError(str(e)) from None


def status_errors(status: int | None) -> list[str]:
    """The names of the STATUS error bits that are set."""
    if status is None:
        return []
    return [n for n in STATUS_ERRORS if getattr(regs, f"STATUS_{n}").get(status)]


def record_text(records: np.ndarray, i: int) -> str:
    """Record i as a tuple of ints, "none" past the end (for a first difference)."""
    return str(tuple(int(v) for v in records[i])) if i < len(records) else "none"
