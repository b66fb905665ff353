"""Building the RTL under GHDL and running a cocotb module on it: the one place that
does it, for the testbenches (tb/harness.py), `fastnms sim` (sim/run.py) and the bench
(flows/bench/bench.py).

Each caller picks a build directory per top level and generic set, so generic sets
never share a compiled library; the build runs under an exclusive lock and the
simulation under a shared one, so parallel runs (pytest-xdist workers, bench jobs)
can share a build but never re-analyse a library while another run elaborates it.
"""

from __future__ import annotations

import fcntl
import subprocess
import sys
from pathlib import Path

from .sources import REPO, rtl_sources

BUILD = REPO / "build" / "sim"


def build_and_run(
    toplevel: str,
    module: str,
    generics: dict[str, object],
    *,
    build_dir: Path,
    test_dir: Path,
    plusargs: list[str],
    extra_env: dict[str, str],
    seed: int | None = None,
    testcase: str | None = None,
    log_file: Path | None = None,
    always: bool = False,
    extra_sources: tuple[Path, ...] = (),
) -> tuple[int, int]:
    """Build `toplevel` from rtl/ into `build_dir` and run the cocotb module `module`
    (a dotted name importable from the repository root or the installed package) on
    it with `generics`; returns (tests, failed) from its results file. `plusargs`
    are GHDL run-time options; `log_file` takes the build's and the simulator's
    output (the console otherwise); `extra_sources` are compiled after rtl/ (a
    synthesis probe, for one)."""
    from cocotb_tools.check_results import get_results
    from cocotb_tools.runner import get_runner

    build_dir.mkdir(parents=True, exist_ok=True)
    test_dir.mkdir(parents=True, exist_ok=True)
    # The runner hands sys.path to the simulator's Python as PYTHONPATH: the
    # testbenches (tb) and the flows are packages of the repository root.
    if str(REPO) not in sys.path:
        sys.path.insert(0, str(REPO))
    runner = get_runner("ghdl")
    with open(build_dir / ".lock", "w") as lock:
        fcntl.flock(lock, fcntl.LOCK_EX)
        runner.build(
            sources=[*rtl_sources(), *extra_sources],
            hdl_toplevel=toplevel,
            build_args=["--std=08"],
            build_dir=build_dir,
            always=always,
            log_file=log_file,
        )
        fcntl.flock(lock, fcntl.LOCK_SH)
        results = runner.test(
            test_module=module,
            hdl_toplevel=toplevel,
            parameters=generics,
            test_args=["--std=08", f"--workdir={build_dir}"],
            plusargs=plusargs,
            testcase=testcase,
            seed=seed,
            extra_env=extra_env,
            build_dir=build_dir,
            test_dir=test_dir,
            results_xml=str(test_dir / "results.xml"),
            log_file=log_file,
        )
    return get_results(Path(results))


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
