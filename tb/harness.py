"""Runs cocotb testbenches under GHDL from pytest.

The RTL is analysed once into a library that every top level and generic set
shares (fastnms.sim.ghdl); each test gets its own directory under
build/sim/<toplevel>-<generics>/ for its results and log. Each cocotb test can be
its own pytest item (`cocotb_tests` lists a module's tests for parametrize).

Seeds: FASTNMS_SEED sets the seed of every test; otherwise each test uses a
fixed seed derived from its pytest node id, so a run is reproducible. The seed is
printed (pytest shows it on failure) and logged by the testbench. The simulator's
output (or the analysis's, when it fails) goes to sim.log in the test's
directory, as a long run's log can be large; pytest shows its path and last 200
lines when the test fails.
"""

from __future__ import annotations

import os
import re
import zlib
from pathlib import Path

from fastnms.sim.ghdl import BUILD, build_and_run
from fastnms.sim.sources import REPO

TB = REPO / "tb"


def test_seed(name: str) -> int:
    """The seed for one test: FASTNMS_SEED if set, else a stable hash of its name."""
    env = os.environ.get("FASTNMS_SEED")
    if env:
        return int(env, 0)
    return zlib.crc32(name.encode()) & 0x7FFFFFFF


_COCOTB_TEST = re.compile(r"^@cocotb\.test\b[^\n]*\n(?:@[^\n]*\n)*async def (\w+)", re.MULTILINE)


def _module_file(module: str) -> Path:
    found = sorted(TB.rglob(f"{module}.py"))
    assert len(found) == 1, f"{len(found)} testbench modules {module}.py under tb/"
    return found[0]


def cocotb_tests(module: str) -> list[str]:
    """The cocotb tests a testbench module defines, in file order: the values
    `testcase` takes, so that each becomes a pytest item of its own."""
    names = _COCOTB_TEST.findall(_module_file(module).read_text())
    assert names, f"{module}.py defines no cocotb test"
    return names


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
    extra_sources: tuple[Path, ...] = (),
) -> None:
    """Build `toplevel` with `generics` and run the cocotb tests of `module`.

    `module` names a Python module in tb/ or one of its folders (`axi_frames_tb`); `env` reaches the
    testbench as environment variables; `extra_sources` are compiled after rtl/ (a synthesis
    wrapper entity, for one). Fails unless at least one test ran and none failed.
    """
    seed = test_seed(name)
    print(f"seed={seed} (set FASTNMS_SEED={seed} to repeat)")
    key = "-".join(f"{k}{v}" for k, v in sorted(generics.items()))
    test_dir = BUILD / f"{toplevel}-{key}" / _slug(name)

    dotted = ".".join(_module_file(module).relative_to(REPO).with_suffix("").parts)

    log = test_dir / "sim.log"
    try:
        tests, failed = build_and_run(
            toplevel,
            dotted,
            generics,
            test_dir=test_dir,
            # GHDL run-time options go after the top-level name, where plusargs go.
            # An RTL assertion of severity error (a broken input contract)
            # stops the simulation, so the test fails. numeric_std's warnings are
            # off: pipeline registers hold U until the first pixel reaches them, and
            # a top waiting for its first frame printed hundreds per clock (300 MB
            # of log, most of the test's time); a wrong value is caught by the
            # scoreboards, which compare every output with the golden model.
            plusargs=["--ieee-asserts=disable", "--assert-level=error"],
            extra_env={"TB_GENERICS": repr(generics), **(env or {})},
            seed=seed,
            testcase=testcase,
            log_file=log,
            extra_sources=extra_sources,
        )
    finally:
        _print_tail(log)
    assert tests > 0, f"{module}: no cocotb test ran (testcase={testcase!r}); see {log}"
    assert failed == 0, f"{module}: {failed} of {tests} cocotb tests failed (seed={seed}, {log})"


def _print_tail(log: Path, lines: int = 200) -> None:
    """The last lines of a simulation log, for pytest to show if the test fails."""
    if not log.exists():
        return
    with open(log, "rb") as f:
        f.seek(max(0, log.stat().st_size - 200 * lines))
        tail = f.read().decode(errors="replace").splitlines()[-lines:]
    print(f"--- last {len(tail)} lines of {log} ---")
    print("\n".join(tail))
