"""The fast simulation engine: fastnms_axi as GHDL synthesizes it (`ghdl --synth
--out=verilog`), compiled with Verilator together with sim/verilator_harness.cpp,
which drives its ports from C++ as the cocotb bench does.

One executable per generic set, in build/vsim/<top>-<generics>-<key>/, where
the key is a hash of everything the executable is made from (the RTL files,
the harness, the register header, the tool versions and flags): a changed RTL
file means a new key and a new build; builds are locked against parallel runs.
The engine simulates the synthesized netlist, so it also checks GHDL's
synthesis of the RTL against the golden model.
"""

from __future__ import annotations

import fcntl
import hashlib
import os
import re
import shutil
import subprocess
import tempfile
import time
from collections.abc import Callable, Sequence
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from .ghdl import tool_version
from .sources import REPO, RTL, rtl_sources
from .timing import Timing

HARNESS = Path(__file__).with_name("verilator_harness.cpp")
REGS_HEADER = REPO / "sw" / "fastnms_regs.h"
TOP = "fastnms_axi"
TOP_FILE = RTL / "top" / "fastnms_axi.vhd"
BUILD = REPO / "build" / "vsim"
# --x-initial unique: registers and memories start from values a run can
# randomise (+verilator+rand+reset+2), so a test can show the results do not
# depend on them. The netlist has a port named `soft`, a SystemVerilog keyword.
VERILATOR_FLAGS = [
    "--cc",
    "--exe",
    "--build",
    "-O3",
    "--x-assign",
    "fast",
    "--x-initial",
    "unique",
    "--default-language",
    "1364-2005",
    "-Wno-fatal",
    "-Wno-lint",
    "-Wno-style",
    "-Wno-UNOPTFLAT",  # the segmented counter's carry chain, a vector built bit by bit
    "-Wno-SYMRSVDWORD",  # the port `interrupt`
]
CXXFLAGS = "-O2"
_ATTRIBUTE_SPEC = re.compile(r"^\s*attribute\s+x_interface_\w+\s+of\s+[^;]*;[ \t]*\n", re.I | re.M)


class EngineError(Exception):
    """The engine cannot build or run; the message says what is missing or where the log is."""


@dataclass
class RawFrame:
    first_pixel: int
    last_pixel: int
    last_record: int
    words: np.ndarray  # uint64 record words in output order
    input_stalls: int
    word_clocks: np.ndarray  # int64: the clock of each word's handshake


@dataclass
class RawRun:
    frames: list[RawFrame]
    cycles: int  # first pixel of the first frame to the last record of the last, inclusive
    input_stalls: int
    status: int
    frame_count: int
    build_seconds: float | None  # None: the executable was already built


def strip_interface_attributes(text: str) -> tuple[str, int]:
    """fastnms_axi.vhd without its X_INTERFACE attribute specifications (GHDL 2.0's
    synthesis stops on attributes of input ports; only Vivado's packager reads them)."""
    return _ATTRIBUTE_SPEC.subn("", text)


def synthesizable_sources(copy: Path) -> list[Path]:
    """rtl_sources() with fastnms_axi.vhd replaced by a copy at `copy` without its
    X_INTERFACE attributes."""
    text, count = strip_interface_attributes(TOP_FILE.read_text())
    assert count > 0, "no X_INTERFACE attribute specifications found in fastnms_axi.vhd"
    copy.parent.mkdir(parents=True, exist_ok=True)
    if not copy.exists() or copy.read_text() != text:
        copy.write_text(text)
    return [copy if f == TOP_FILE else f for f in rtl_sources()]


def missing_tools() -> list[str]:
    """The tools the engine needs and this machine lacks."""
    missing = [t for t in ("ghdl", "verilator", "make") if shutil.which(t) is None]
    if shutil.which("g++") is None and shutil.which("c++") is None:
        missing.append("g++")
    return missing


def _check_tools() -> None:
    missing = missing_tools()
    if missing:
        raise EngineError(
            f"the fast simulation engine needs {', '.join(missing)}, not found on PATH "
            "(Debian: sudo apt-get install -y ghdl verilator g++ make; `make setup` does it as "
            "root), or use --engine cocotb"
        )


def build_key(generics: dict[str, object], files: Sequence[Path] | None = None) -> str:
    """A hash of the generics, the files an executable is made from (by default the
    RTL, this engine's harness and the register header), the tools and the flags."""
    h = hashlib.sha256()
    for name in sorted(generics):
        h.update(f"{name}={generics[name]}\n".encode())
    for path in files if files is not None else [*rtl_sources(), HARNESS, REGS_HEADER]:
        h.update(path.name.encode())
        h.update(path.read_bytes())
    for tool in (["ghdl", "--version"], ["verilator", "--version"], ["g++", "--version"]):
        h.update(tool_version(tool).encode())
    h.update(" ".join([*VERILATOR_FLAGS, CXXFLAGS]).encode())
    return h.hexdigest()[:16]


def build_dir(generics: dict[str, object]) -> Path:
    name = "-".join(f"{k}{v}" for k, v in sorted(generics.items()))
    return BUILD / f"{TOP}-{name}-{build_key(generics)}"


def _run_logged(command: list[str], log, cwd: Path | None = None) -> None:
    log.write(("$ " + " ".join(command) + "\n").encode())
    log.flush()
    result = subprocess.run(command, stdout=log, stderr=subprocess.STDOUT, cwd=cwd)
    if result.returncode != 0:
        raise EngineError(f"`{command[0]}` failed; see {log.name}")


def build(
    generics: dict[str, object], announce: Callable[[str], None] | None = None
) -> tuple[Path, float | None]:
    """The engine's executable for `generics`, built if needed; returns it and the
    build's seconds (None when it was already built)."""
    _check_tools()
    where = build_dir(generics)
    where.mkdir(parents=True, exist_ok=True)
    exe = where / "fastnms_vsim"
    with open(where / ".lock", "w") as lock:
        fcntl.flock(lock, fcntl.LOCK_EX)
        if exe.exists():
            return exe, None
        if announce:
            announce(f"building the fast simulation engine in {where.relative_to(REPO)} ...")
        start = time.perf_counter()
        work = where / "ghdl"
        shutil.rmtree(work, ignore_errors=True)
        work.mkdir()
        netlist = where / f"{TOP}.v"
        with open(where / "build.log", "wb") as log:
            sources = synthesizable_sources(where / "fastnms_axi_no_attributes.vhd")
            _run_logged(["ghdl", "-a", "--std=08", f"--workdir={work}", *map(str, sources)], log)
            gens = [f"-g{k}={v}" for k, v in generics.items()]
            with open(netlist, "wb") as out:
                cmd = ["ghdl", "--synth", "--std=08", f"--workdir={work}", *gens]
                cmd += ["--out=verilog", TOP]
                log.write(("$ " + " ".join(cmd) + f" > {netlist.name}\n").encode())
                log.flush()
                if subprocess.run(cmd, stdout=out, stderr=log).returncode != 0:
                    raise EngineError(f"GHDL's synthesis failed; see {log.name}")
            netlist.write_text(fix_bit_strings(netlist.read_text()))
            cflags = f"{CXXFLAGS} -I{REGS_HEADER.parent}"
            cmd = ["verilator", *VERILATOR_FLAGS, "-j", str(os.cpu_count() or 1)]
            cmd += ["--top-module", TOP, "-CFLAGS", cflags, "--Mdir", str(where / "obj")]
            cmd += [str(netlist), str(HARNESS), "-o", str(exe)]
            _run_logged(cmd, log)
        shutil.rmtree(work, ignore_errors=True)
        # Builds of the same generics from older sources are of no more use.
        for old in where.parent.glob(where.name.rsplit("-", 1)[0] + "-*"):
            if old != where and len(old.name) == len(where.name):
                shutil.rmtree(old, ignore_errors=True)
        return exe, time.perf_counter() - start


# GHDL 2.0 writes a constant vector of more than 32 bits as a Verilog string
# ("0101..."), which Verilog reads as ASCII characters: the netlist would differ
# from the RTL. The build rewrites each such string as the sized binary literal
# it stands for (a synthesized netlist has no other strings).
_BIT_STRING = re.compile(r'"([01]+)"')


def fix_bit_strings(verilog: str) -> str:
    """The netlist with every string of 0s and 1s written as a sized binary literal."""
    return _BIT_STRING.sub(lambda m: f"{len(m.group(1))}'b{m.group(1)}", verilog)


def run(
    exe: Path,
    frames: Sequence[tuple[np.ndarray, int]],
    timing: Timing,
    progress: Callable[[int, int], None] | None = None,
    power_up_seed: int | None = None,
    ppc: int = 1,
    budget: tuple[int, int] | None = None,
    min_area: int | None = None,
) -> RawRun:
    """Send `frames` (image, threshold) back to back through the executable, in
    beats of `ppc` pixels (the build's PPC generic), with BUDGET = `budget` (cell,
    per_cell) and MIN_AREA = `min_area` written for every frame when given.
    `power_up_seed` randomises the netlist's initial register and memory values."""
    with tempfile.TemporaryDirectory(dir=exe.parent) as tmp:
        job, pixels, records = Path(tmp, "job"), Path(tmp, "pixels"), Path(tmp, "records")
        lines = [f"seed {timing.seed}\n", f"hblank {timing.hblank}\n", f"vblank {timing.vblank}\n"]
        lines.append(f"ppc {ppc}\n")
        if budget is not None:
            lines.append(f"budget {budget[0]} {budget[1]}\n")
        if min_area is not None:
            lines.append(f"min_area {min_area}\n")
        lines += [timing.idle.job_line("idle"), timing.stall.job_line("stall")]
        with open(pixels, "wb") as f:
            for img, threshold in frames:
                h, w = img.shape
                lines.append(f"frame {w} {h} {threshold}\n")
                f.write(np.ascontiguousarray(img, dtype=np.uint8).tobytes())
        job.write_text("".join(lines))
        cmd = [str(exe), str(job), str(pixels), str(records)]
        if power_up_seed is not None:
            cmd += [f"+verilator+seed+{power_up_seed}", "+verilator+rand+reset+2"]
        proc = subprocess.Popen(cmd, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
        errors = []
        assert proc.stderr is not None and proc.stdout is not None
        for line in proc.stderr:
            parts = line.split()
            if len(parts) == 3 and parts[0] == "progress":
                if progress is not None:
                    progress(int(parts[1]), int(parts[2]))
            else:
                errors.append(line.strip())
        out = proc.stdout.read()
        if proc.wait() != 0:
            raise EngineError("; ".join(errors) or f"{exe.name} exited with {proc.returncode}")
        beats = np.fromfile(records, dtype="<u8").reshape(-1, 2)
        words, clocks = beats[:, 0], beats[:, 1].astype(np.int64)
    parsed: list[RawFrame] = []
    at = 0
    done = None
    for line in out.splitlines():
        parts = line.split()
        if parts[0] == "frame":
            first, last_pixel, last_record, count, stalls = (int(v) for v in parts[2:7])
            parsed.append(
                RawFrame(
                    first,
                    last_pixel,
                    last_record,
                    words[at : at + count],
                    stalls,
                    clocks[at : at + count],
                )
            )
            at += count
        elif parts[0] == "done":
            done = [int(v) for v in parts[1:5]]
    if done is None or len(parsed) != len(frames) or at != words.size:
        raise EngineError(f"{exe.name} wrote an incomplete result")
    return RawRun(
        frames=parsed,
        cycles=parsed[-1].last_record - parsed[0].first_pixel + 1,
        input_stalls=done[1],
        status=done[2],
        frame_count=done[3],
        build_seconds=None,
    )
