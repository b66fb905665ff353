"""The pyramid engine: seven fastnms_resize in a chain (sim/fastnms_resize_chain.vhd)
as GHDL synthesizes them, compiled by Verilator with sim/pyramid_harness.cpp: an
image in, cv2.ORB's pyramid levels out, as the RTL computes them (`fastnms pyramid
--rtl`, docs/fastnms_resize.md).

One executable per (MAX_WIDTH, MAX_HEIGHT, LEVELS), in build/vsim/pyramid-..., keyed
by the RTL files, the wrapper, the harness and the tool versions, as the top's fast
engine (sim/verilator.py) is.
"""

from __future__ import annotations

import fcntl
import os
import shutil
import subprocess
import tempfile
import time
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from .sources import rtl_sources
from .verilator import (
    BUILD,
    CXXFLAGS,
    VERILATOR_FLAGS,
    EngineError,
    _check_tools,
    _run_logged,
    build_key,
    fix_bit_strings,
)

TOP = "fastnms_resize_chain"
WRAPPER = Path(__file__).with_name("fastnms_resize_chain.vhd")
HARNESS = Path(__file__).with_name("pyramid_harness.cpp")


@dataclass
class PyramidRun:
    """The levels 1 .. LEVELS - 1 as the chain gave them, and what the run measured."""

    levels: list[np.ndarray]
    clocks: int  # from the first pixel offered to the last pixel out
    input_held: int  # clocks the input waited
    link_stalls: int  # clocks a step's output waited for the next step
    errors: int  # error pulses of all steps


def build(max_width: int, max_height: int, levels: int) -> tuple[Path, float | None]:
    """The executable for these generics, built if needed; returns it and the build's
    seconds (None when it was already built)."""
    _check_tools()
    generics = {"LEVELS": levels, "MAX_WIDTH": max_width, "MAX_HEIGHT": max_height}
    name = "-".join(f"{k}{v}" for k, v in sorted(generics.items()))
    key = build_key(generics, [*rtl_sources(), WRAPPER, HARNESS])
    where = BUILD / f"pyramid-{name}-{key}"
    where.mkdir(parents=True, exist_ok=True)
    exe = where / "fastnms_pyramid_vsim"
    with open(where / ".lock", "w") as lock:
        fcntl.flock(lock, fcntl.LOCK_EX)
        if exe.exists():
            return exe, None
        start = time.perf_counter()
        work = where / "ghdl"
        shutil.rmtree(work, ignore_errors=True)
        work.mkdir()
        netlist = where / f"{TOP}.v"
        with open(where / "build.log", "wb") as log:
            sources = [*rtl_sources(), WRAPPER]
            _run_logged(["ghdl", "-a", "--std=08", f"--workdir={work}", *map(str, sources)], log)
            with open(netlist, "wb") as out:
                cmd = ["ghdl", "--synth", "--std=08", f"--workdir={work}"]
                cmd += [f"-g{k}={v}" for k, v in generics.items()] + ["--out=verilog", TOP]
                log.write(("$ " + " ".join(cmd) + f" > {netlist.name}\n").encode())
                log.flush()
                if subprocess.run(cmd, stdout=out, stderr=log).returncode != 0:
                    raise EngineError(f"GHDL's synthesis failed; see {log.name}")
            netlist.write_text(fix_bit_strings(netlist.read_text()))
            cmd = ["verilator", *VERILATOR_FLAGS, "-j", str(os.cpu_count() or 1)]
            cmd += ["--top-module", TOP, "-CFLAGS", CXXFLAGS, "--Mdir", str(where / "obj")]
            cmd += [str(netlist), str(HARNESS), "-o", str(exe)]
            _run_logged(cmd, log)
        shutil.rmtree(work, ignore_errors=True)
        return exe, time.perf_counter() - start


def run(exe: Path, img: np.ndarray, sizes: list[tuple[int, int]]) -> PyramidRun:
    """One frame `img` (level 0, sizes[0]) through the chain; sizes[k] = (w, h) of
    level k (the chain's generics fix how many)."""
    h, w = img.shape
    assert sizes[0] == (w, h), (sizes[0], img.shape)
    with tempfile.TemporaryDirectory(dir=exe.parent) as tmp:
        pixels = Path(tmp, "pixels")
        pixels.write_bytes(np.ascontiguousarray(img, np.uint8).tobytes())
        args = [str(v) for size in sizes for v in size]
        done = subprocess.run(
            [str(exe), str(pixels), str(Path(tmp, "level")), *args],
            capture_output=True,
            text=True,
        )
        if done.returncode != 0:
            raise EngineError(f"the pyramid engine failed: {done.stderr.strip()}")
        fields = done.stdout.split()
        if len(fields) != 5 or fields[0] != "done":
            raise EngineError(f"the pyramid engine said {done.stdout!r}")
        levels = []
        for k, (lw, lh) in enumerate(sizes[1:], start=1):
            data = np.frombuffer(Path(tmp, f"level{k}.raw").read_bytes(), np.uint8)
            if data.size != lw * lh:
                raise EngineError(f"level {k}: {data.size} pixels out, {lw * lh} expected")
            levels.append(data.reshape(lh, lw).copy())
    clocks, held, stalls, errors = (int(v) for v in fields[1:])
    return PyramidRun(levels, clocks, held, stalls, errors)
