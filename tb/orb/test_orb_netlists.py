"""The ORB units as GHDL synthesizes them: each unit's Verilog netlist (`ghdl --synth
--out=verilog`, the fast engine's netlist, sim/verilator.py) under Icarus Verilog, driven by
the unit's own cocotb testbench against the golden model. The RTL under GHDL passes the
same testbenches (test_orb_units.py); a failure here is a difference between GHDL's
synthesis and its simulation of the RTL, which the fast engine would inherit."""

from __future__ import annotations

import subprocess
from pathlib import Path

import pytest
from cocotb_tools.check_results import get_results
from cocotb_tools.runner import get_runner
from fastnms.sim.sources import REPO, rtl_sources
from fastnms.sim.verilator import fix_bit_strings

from tb import harness

CASES = [
    pytest.param("fastnms_f32_mul", "f32_tb", {}, {"TB_UNIT": "mul", "TB_COUNT": "3000"}, id="mul"),
    pytest.param("fastnms_f32_add", "f32_tb", {}, {"TB_UNIT": "add", "TB_COUNT": "3000"}, id="add"),
    pytest.param("fastnms_orb_angle", "angle_tb", {}, {"TB_COUNT": "300"}, id="angle"),
    pytest.param("fastnms_orb_rotate", "rotate_tb", {"LANES": 8}, {"TB_COUNT": "20"}, id="rotate"),
    pytest.param(
        "fastnms_orb_cos_sin",
        "cos_sin_tb",
        {},
        {"TB_COUNT": "300"},
        id="cos_sin",
        marks=pytest.mark.slow,
    ),
    pytest.param(
        "fastnms_orb_sample",
        "sample_tb",
        {"LANES": 8},
        {"TB_COUNT": "20"},
        id="sample",
        marks=pytest.mark.slow,
    ),
]


@pytest.mark.parametrize(("entity", "module", "generics", "env"), CASES)
def test_netlist_equals_the_model(request, entity, module, generics, env):
    where = harness.BUILD / f"netlist-{entity}"
    work = where / "ghdl"
    work.mkdir(parents=True, exist_ok=True)
    sources = [str(p) for p in rtl_sources()]
    subprocess.run(["ghdl", "-a", "--std=08", f"--workdir={work}", *sources], check=True)
    netlist = where / f"{entity}.v"
    gens = [f"-g{k}={v}" for k, v in generics.items()]
    cmd = ["ghdl", "--synth", "--std=08", f"--workdir={work}", *gens, "--out=verilog", entity]
    with open(netlist, "w") as out:
        subprocess.run(cmd, stdout=out, stderr=subprocess.DEVNULL, check=True)
    netlist.write_text(fix_bit_strings(netlist.read_text()))
    runner = get_runner("icarus")
    runner.build(
        verilog_sources=[netlist],
        hdl_toplevel=entity,
        build_dir=where,
        always=True,
        timescale=("1ns", "1ps"),
    )
    results = runner.test(
        test_module=f"tb.orb.{module}",
        hdl_toplevel=entity,
        build_dir=where,
        test_dir=where,
        seed=harness.test_seed(request.node.nodeid),
        extra_env={"TB_GENERICS": repr(generics), "PYTHONPATH": str(REPO), **env},
    )
    tests, failed = get_results(Path(results))
    assert tests > 0 and failed == 0, f"{entity}: the netlist differs from the model"
