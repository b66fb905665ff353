"""Shared by the tests of flows/vivado_check: sandboxes (copies of vivado/,
constraints/ and rtl/ under build/), dry runs checked by stubcheck, and the
answers the stub gives where a script reads one back from Vivado."""

from __future__ import annotations

import re
import shutil
from dataclasses import dataclass
from pathlib import Path

from fastnms.sim.sources import REPO

from flows.vivado_check import stubcheck, tclcheck, xinterface

VIVADO = REPO / "vivado"
XDC = REPO / "constraints" / "fastnms_ooc.xdc"
TOP = REPO / "rtl" / "top" / "fastnms_axi.vhd"
WORK = REPO / "build" / "test_vivado_tcl"
PART = "xc7z020clg484-1"

# What Vivado would answer where the scripts read a value back.
PACKAGE_RESULTS = {
    "get_property VALUE *POLARITY*": "ACTIVE_LOW",
    "get_property VALUE *TUSER_WIDTH*": "1",
}
BD_RESULTS = {
    "get_property CONFIG.PCW_ACT_FPGA0_PERIPHERAL_FREQMHZ": "142.857132",
    "get_board_parts": "avnet.com:zedboard:part0:1.4 xilinx.com:zc702:part0:1.4",
}


def merge(results: dict[str, str], defaults: dict[str, str]) -> dict[str, str]:
    """Stub results: `results` first (the stub takes the first key that
    matches), then the `defaults` they do not replace."""
    return {**results, **{k: v for k, v in defaults.items() if k not in results}}


def sandbox(name: str, *, with_top: bool = True) -> Path:
    """A copy of vivado/, constraints/ and rtl/ under build/ (without
    rtl/top/fastnms_axi.vhd when `with_top` is false)."""
    root = WORK / name
    shutil.rmtree(root, ignore_errors=True)
    for folder in ("vivado", "constraints", "rtl"):
        shutil.copytree(REPO / folder, root / folder)
    if not with_top:
        (root / "rtl" / "top" / "fastnms_axi.vhd").unlink()
    return root


def fake_ip_repo(root: Path) -> Path:
    repo = root / "ip"
    repo.mkdir(parents=True, exist_ok=True)
    (repo / "component.xml").write_text("<placeholder/>\n")
    return repo


def mutate(path: Path, old: str, new: str) -> None:
    """Replaces the one occurrence of `old` in `path` by `new`."""
    text = path.read_text()
    assert text.count(old) == 1, f"{old!r} occurs {text.count(old)} times in {path.name}"
    path.write_text(text.replace(old, new))


def ip_vlnv() -> str:
    text = (VIVADO / "fastnms_common.tcl").read_text()
    fields = [
        re.search(rf"variable {name}\s+(\S+)", text).group(1)
        for name in ("vendor", "library", "name", "version")
    ]
    return ":".join(fields)


@dataclass
class Run:
    calls: list[list[str]]
    error: str | None
    problems: list[str]  # stubcheck's

    def of(self, command: str) -> list[list[str]]:
        return [c for c in self.calls if c[0] == command]

    @property
    def text(self) -> str:
        return "\n".join(" ".join(c) for c in self.calls)

    def assert_clean(self) -> None:
        assert self.error is None, self.error
        assert not self.problems, "Vivado would reject:\n" + "\n".join(self.problems)


def dry_run(root: Path, script: str, argv: list[str], results: dict[str, str] | None = None) -> Run:
    """`script` of the sandbox `root` dry-run with Vivado stubbed, its calls
    checked against vivado_api (stubcheck) and the sandbox's top level."""
    top = (
        xinterface.load(root / "rtl" / "top" / "fastnms_axi.vhd")
        if (root / "rtl" / "top" / "fastnms_axi.vhd").exists()
        else None
    )
    calls, error = tclcheck.dry_run(root / "vivado" / script, argv, results)
    ips = {}
    if top is not None:
        ip = stubcheck.top_ip(top, ip_vlnv())
        ips[ip.vlnv] = ip
    return Run(calls, error, stubcheck.check(calls, ips, top))
