"""Runs cocotb testbenches under GHDL from pytest.

Each (toplevel, generics) pair gets its own build directory under build/sim, so
generic sets never share a compiled library and pytest-xdist workers can run in
parallel. Seeds: FASTNMS_SEED sets the seed of every test; otherwise each test
uses a fixed seed derived from its name, so a run is reproducible. The seed is
printed (pytest shows it on failure) and logged by the testbench.
"""

from __future__ import annotations

import fcntl
import os
import re
import sys
import zlib
from pathlib import Path

from cocotb_tools.check_results import get_results
from cocotb_tools.runner import get_runner
from fastnms.sim.sources import REPO, rtl_sources

TB = REPO / "tb"
BUILD = REPO / "build" / "sim"


def test_seed(name: str) -> int:
    """The seed for one test: FASTNMS_SEED if set, else a stable hash of its name."""
    env = os.environ.get("FASTNMS_SEED")
    if env:
        return int(env, 0)
    return zlib.crc32(name.encode()) & 0x7FFFFFFF


def _slug(text: str) -> str:
    return re.sub(r"[^A-Za-z0-9_.-]+", "_", text).strip("_")


def run_cocotb(
    toplevel: str,
    module: str,
    generics: dict[str, object],
    *,
    testcase: str | None = None,
    env: dict[str, str] | None = None,
    name: str,
) -> None:
    """Build `toplevel` with `generics` and run the cocotb tests of `module`.

    `module` names a Python module in tb/ or one of its folders (`axi_tb`); `env` reaches the
    testbench as environment variables. Fails unless at least one test ran and
    none failed.
    """
    seed = test_seed(name)
    print(f"seed={seed} (set FASTNMS_SEED={seed} to repeat)")
    key = "-".join(f"{k}{v}" for k, v in sorted(generics.items()))
    build_dir = BUILD / f"{toplevel}-{key}"
    test_dir = build_dir / _slug(name)
    test_dir.mkdir(parents=True, exist_ok=True)

    found = sorted(TB.rglob(f"{module}.py"))
    assert len(found) == 1, f"{len(found)} testbench modules {module}.py under tb/"
    dotted = ".".join(found[0].relative_to(REPO).with_suffix("").parts)
    # The runner hands sys.path to the simulator's Python as PYTHONPATH: the
    # testbenches are the package `tb` of the repository root.
    if str(REPO) not in sys.path:
        sys.path.insert(0, str(REPO))

    runner = get_runner("ghdl")
    # Build under an exclusive lock, simulate under a shared one: a parallel
    # worker must not re-analyse the library while another one elaborates it.
    with open(build_dir / ".lock", "w") as lock:
        fcntl.flock(lock, fcntl.LOCK_EX)
        runner.build(
            sources=rtl_sources(),
            hdl_toplevel=toplevel,
            build_args=["--std=08"],
            build_dir=build_dir,
            always=False,
        )
        fcntl.flock(lock, fcntl.LOCK_SH)
        results = runner.test(
            test_module=dotted,
            hdl_toplevel=toplevel,
            parameters=generics,
            test_args=["--std=08", f"--workdir={build_dir}"],
            # GHDL run-time options go after the top-level name, where plusargs go.
            # An RTL assertion of severity error (a broken input contract)
            # stops the simulation, so the test fails.
            plusargs=["--ieee-asserts=disable-at-0", "--assert-level=error"],
            testcase=testcase,
            seed=seed,
            extra_env={"TB_GENERICS": repr(generics), **(env or {})},
            build_dir=build_dir,
            test_dir=test_dir,
            results_xml=str(test_dir / "results.xml"),
        )
    tests, failed = get_results(Path(results))
    assert tests > 0, f"{module}: no cocotb test ran (testcase={testcase!r})"
    assert failed == 0, f"{module}: {failed} of {tests} cocotb tests failed (seed={seed})"
