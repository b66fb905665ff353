"""The FuseSoC core description, fastnms.core.

Its rtl fileset lists the RTL in compile order; its sim target (GHDL, the
self-checking tb/vhdl/fastnms_smoke_tb.vhd) passes, and fails when the
testbench's expectation is wrong; its synth target sets up a Vivado project
for the xc7z020 (Vivado itself is not run); the testbench's vectors are what
the golden model gives today.
"""

from __future__ import annotations

import importlib.util
import os
import re
import shutil
import subprocess
import sys
import time
from pathlib import Path

import pytest
import yaml
from fastnms.sim.sources import REPO, compile_order, order_problems, tracked_rtl_files

from flows.vivado_check import tclcheck

CORE = REPO / "fastnms.core"
VERSION = (REPO / "VERSION").read_text().strip()
VLNV = f"::fastnms:{VERSION}"
WORK = REPO / "build" / "fusesoc"
FUSESOC = Path(sys.executable).with_name("fusesoc")
VECTORS = REPO / "tb" / "vhdl" / "fastnms_smoke_vectors_pkg.vhd"
PASS_LINE = "fastnms_smoke_tb: PASS"

pytestmark = pytest.mark.skipif(not FUSESOC.exists(), reason="fusesoc is not installed in .venv")


def core() -> dict:
    return yaml.safe_load(CORE.read_text())


def hide_from_core_scans() -> None:
    """A FUSESOC_IGNORE file in build/fusesoc: the copies of the core made
    there are never found by a scan of the repository (--cores-root .)."""
    WORK.mkdir(parents=True, exist_ok=True)
    (WORK / "FUSESOC_IGNORE").touch()


def run_fusesoc(cores_root: Path, work_root: Path, *args: str) -> subprocess.CompletedProcess:
    """`fusesoc run` of fastnms in `work_root`, with an empty configuration and
    its own cache, so nothing outside the repository's build/ is read or
    written."""
    hide_from_core_scans()
    shutil.rmtree(work_root, ignore_errors=True)
    work_root.mkdir(parents=True)
    config = work_root.parent / f"{work_root.name}.conf"
    config.write_text("")
    home = work_root.parent / f"{work_root.name}.home"
    env = {
        **os.environ,
        "XDG_CONFIG_HOME": str(home / "config"),
        "XDG_CACHE_HOME": str(home / "cache"),
        "XDG_DATA_HOME": str(home / "data"),
    }
    command = [
        str(FUSESOC),
        "--config",
        str(config),
        "--cores-root",
        str(cores_root),
        "run",
        "--work-root",
        str(work_root),
        *args,
        VLNV,
    ]
    return subprocess.run(
        command, cwd=REPO, env=env, capture_output=True, text=True, timeout=120, check=False
    )


# ---- the file lists ----------------------------------------------------------------


def test_rtl_fileset_is_the_rtl_in_compile_order() -> None:
    rtl = core()["filesets"]["rtl"]
    assert rtl["file_type"] == "vhdlSource-2008"
    listed = [REPO / f for f in rtl["files"]]
    absent = [str(f.relative_to(REPO)) for f in listed if not f.exists()]
    assert not absent, f"fastnms.core lists files that do not exist: {absent}"
    missing = sorted(set(tracked_rtl_files()) - set(listed))
    if missing:
        order = compile_order(sorted(set(listed) | set(missing)))
        lines = "\n".join(f"      - {f.relative_to(REPO)}" for f in order)
        pytest.fail(
            "fastnms.core misses "
            + ", ".join(str(f.relative_to(REPO)) for f in missing)
            + "; its rtl fileset in compile order would be:\n"
            + lines
        )
    assert not order_problems(listed), order_problems(listed)


def test_smoke_testbench_files() -> None:
    files = [REPO / f for f in core()["filesets"]["smoke_tb"]["files"]]
    assert files == [VECTORS, REPO / "tb" / "vhdl" / "fastnms_smoke_tb.vhd"]


def test_smoke_vectors_are_from_the_golden_model() -> None:
    spec = importlib.util.spec_from_file_location(
        "gen_smoke_vectors", REPO / "tb" / "vhdl" / "gen_smoke_vectors.py"
    )
    gen = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(gen)
    assert VECTORS.read_text() == gen.render(), (
        "tb/vhdl/fastnms_smoke_vectors_pkg.vhd is stale: run "
        ".venv/bin/python tb/vhdl/gen_smoke_vectors.py"
    )


# ---- the targets -------------------------------------------------------------------


def test_sim_target_passes() -> None:
    if shutil.which("ghdl") is None:
        pytest.skip("no ghdl")
    start = time.monotonic()
    proc = run_fusesoc(REPO, WORK / "sim", "--target", "sim")
    seconds = time.monotonic() - start
    output = proc.stdout + proc.stderr
    assert proc.returncode == 0, output
    assert PASS_LINE in output, output
    print(f"fusesoc sim: {seconds:.1f} s")
    assert seconds < 60


def test_sim_target_fails_on_a_wrong_expectation() -> None:
    """The same run on a copy whose expected score of the first record is off by
    one: the testbench must stop with a failure, and fusesoc must say so."""
    if shutil.which("ghdl") is None:
        pytest.skip("no ghdl")
    hide_from_core_scans()
    root = WORK / "negative" / "root"
    shutil.rmtree(root, ignore_errors=True)
    root.mkdir(parents=True)
    shutil.copy(CORE, root / CORE.name)
    for f in [*core()["filesets"]["rtl"]["files"], *core()["filesets"]["smoke_tb"]["files"]]:
        (root / f).parent.mkdir(parents=True, exist_ok=True)
        shutil.copy(REPO / f, root / f)
    vectors = root / VECTORS.relative_to(REPO)
    text = vectors.read_text()
    first = re.search(r"SMOKE_RECORDS[^\n]*\n\s*\(\n\s*(\d+), (\d+), (\d+)", text)
    x, y, score = (int(v) for v in first.groups())
    start, end = first.span(3)
    vectors.write_text(text[:start] + str(score + 1) + text[end:])

    proc = run_fusesoc(root, WORK / "negative" / "sim", "--target", "sim")
    output = proc.stdout + proc.stderr
    assert proc.returncode != 0, output
    assert PASS_LINE not in output
    expected = f"frame 0 record 0: got ({x}, {y}, {score}), expected ({x}, {y}, {score + 1})"
    assert expected in output, output


def test_synth_target_sets_up_a_vivado_project() -> None:
    """Setup only (no Vivado here): the project script FuseSoC generates."""
    work = WORK / "synth"
    proc = run_fusesoc(REPO, work, "--setup", "--target", "synth")
    assert proc.returncode == 0, proc.stdout + proc.stderr
    project = work / f"fastnms_{VERSION}.tcl"
    text = project.read_text()
    assert "set_property part xc7z020clg484-1 [current_project]" in text
    assert "set_property top fastnms_axi [current_fileset]" in text
    read = re.findall(rf"read_vhdl -vhdl2008 \{{src/fastnms_{re.escape(VERSION)}/(\S+)\}}", text)
    assert read == core()["filesets"]["rtl"]["files"]
    if tclcheck.backend() is not None:
        assert not tclcheck.incomplete_commands(project)
