"""Analysing the RTL under GHDL and running a cocotb module on it: the one place that
does it, for the testbenches (tb/harness.py), `fastnms sim` (sim/run.py) and the bench.

The RTL is analysed once into a library shared by every top level and generic set
(GHDL's mcode back end elaborates at run time, so generics never need a library of
their own): build/sim/lib-<hash of the file list>. The library is re-analysed only
when a file's content changes (a stamp holds the hash of every file), under an
exclusive lock; simulations hold a shared lock, so parallel runs (pytest-xdist
workers, bench jobs) share one analysis and never re-analyse a library while
another run elaborates it. Each run keeps its own directory (`test_dir`) for its
results and log.
"""

from __future__ import annotations

import fcntl
import hashlib
import re
import subprocess
import sys
from contextlib import contextmanager
from pathlib import Path

from .sources import REPO, rtl_sources

BUILD = REPO / "build" / "sim"
LIBRARY = "top"  # the library name cocotb's GHDL runner elaborates from


def library_dir(sources: list[Path]) -> Path:
    """The shared library of one file list (the RTL, plus a test's extra files)."""
    names = "\n".join(str(p.resolve()) for p in sources)
    return BUILD / f"lib-{hashlib.sha256(names.encode()).hexdigest()[:12]}"


def _content_stamp(sources: list[Path]) -> str:
    digest = hashlib.sha256()
    for path in sources:
        digest.update(str(path).encode() + b"\0" + path.read_bytes() + b"\0")
    return digest.hexdigest()


@contextmanager
def analysed(sources: list[Path], log_file: Path | None = None):
    """Analyse `sources` (in compile order) into their shared library unless it is up
    to date; yields the library's directory while holding a shared lock on it."""
    lib = library_dir(sources)
    lib.mkdir(parents=True, exist_ok=True)
    stamp_file = lib / "stamp"
    stamp = _content_stamp(sources)
    with open(lib / ".lock", "w") as lock:
        fcntl.flock(lock, fcntl.LOCK_SH)
        if not stamp_file.exists() or stamp_file.read_text() != stamp:
            fcntl.flock(lock, fcntl.LOCK_EX)
            if not stamp_file.exists() or stamp_file.read_text() != stamp:
                _analyse(lib, sources, log_file)
                stamp_file.write_text(stamp)
            fcntl.flock(lock, fcntl.LOCK_SH)
        yield lib


def _analyse(lib: Path, sources: list[Path], log_file: Path | None) -> None:
    for cf in lib.glob("*.cf"):
        cf.unlink()
    cmd = ["ghdl", "-a", "--std=08", f"--work={LIBRARY}", f"--workdir={lib}", *map(str, sources)]
    result = subprocess.run(cmd, capture_output=True, text=True)
    if result.returncode != 0:
        text = f"$ {' '.join(cmd)}\n{result.stdout}{result.stderr}"
        if log_file is not None:
            log_file.parent.mkdir(parents=True, exist_ok=True)
            log_file.write_text(text)
        raise RuntimeError(f"GHDL analysis failed:\n{text[-4000:]}")


def build_and_run(
    toplevel: str,
    module: str,
    generics: dict[str, object],
    *,
    test_dir: Path,
    plusargs: list[str],
    extra_env: dict[str, str],
    seed: int | None = None,
    testcase: str | None = None,
    log_file: Path | None = None,
    extra_sources: tuple[Path, ...] = (),
) -> tuple[int, int]:
    """Run the cocotb module `module` (a dotted name importable from the repository
    root or the installed package) on `toplevel` with `generics`, the RTL analysed
    once into its shared library; returns (tests, failed) from its results file.
    `plusargs` are GHDL run-time options; `log_file` takes the simulator's output
    (the console otherwise); `testcase` names the cocotb tests to run (comma-separated,
    every test of the module when None); `extra_sources` are analysed after rtl/ (a test's own
    wrapper entity, for one) into a library of their own."""
    from cocotb_tools.check_results import get_results
    from cocotb_tools.runner import get_runner

    test_dir.mkdir(parents=True, exist_ok=True)
    # The runner hands sys.path to the simulator's Python as PYTHONPATH: the
    # testbenches (tb) and the flows are packages of the repository root.
    if str(REPO) not in sys.path:
        sys.path.insert(0, str(REPO))
    runner = get_runner("ghdl")
    with analysed([*rtl_sources(), *extra_sources], log_file) as lib:
        results = runner.test(
            test_module=module,
            hdl_toplevel=toplevel,
            hdl_toplevel_lang="vhdl",
            hdl_toplevel_library=LIBRARY,
            parameters=generics,
            test_args=["--std=08", f"--workdir={lib}"],
            plusargs=plusargs,
            # Exact names: cocotb's own `testcase` would also run every test whose
            # name ends with one of them.
            test_filter=None if testcase is None else _exact(testcase),
            seed=seed,
            extra_env=extra_env,
            build_dir=lib,
            test_dir=test_dir,
            results_xml=str(test_dir / "results.xml"),
            log_file=log_file,
        )
    return get_results(Path(results))


def _exact(testcase: str) -> str:
    """A COCOTB_TEST_FILTER that selects exactly the comma-separated test names."""
    names = [re.escape(n.strip()) for n in testcase.split(",") if n.strip()]
    return r"\.(" + "|".join(names) + ")$"


def tool_version(command: list[str]) -> str:
    """The first line a tool prints for `command` (e.g. [tool, "--version"]), or "unknown"."""
    try:
        result = subprocess.run(command, capture_output=True, text=True)
    except OSError:
        return "unknown"
    lines = (result.stdout or result.stderr).strip().splitlines()
    return lines[0] if lines else "unknown"


def ghdl_version() -> str:
    """The first line of `ghdl --version`, or "unknown"."""
    return tool_version(["ghdl", "--version"])
