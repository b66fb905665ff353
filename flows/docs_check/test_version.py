"""One version source: the file VERSION (MAJOR.MINOR.PATCH).

pyproject.toml reads it (setuptools' dynamic version); the FuseSoC core is
`::fastnms:VERSION` (and the Makefile runs that core); the Vivado IP's version is its
MAJOR.MINOR (vivado/fastnms_common.tcl, and every VLNV written in the scripts' comments and
the READMEs); the register map's version, read back in the VERSION register, is VERSION
(rtl/top/fastnms_regs.toml and the files `make regmap` generates from it); the CHANGELOG
has a section for it. Each test fails when its place disagrees with VERSION.
"""

from __future__ import annotations

import re
import tomllib
from pathlib import Path

import yaml

REPO = Path(__file__).resolve().parents[2]
TEXT = (REPO / "VERSION").read_text()
VERSION = TEXT.strip()
PARTS = tuple(int(p) for p in VERSION.split(".")) if re.fullmatch(r"\d+\.\d+\.\d+", VERSION) else ()
IP_VERSION = ".".join(VERSION.split(".")[:2])


def test_version_file_is_one_semantic_version() -> None:
    assert TEXT == VERSION + "\n", "VERSION: one line, MAJOR.MINOR.PATCH and a newline"
    assert len(PARTS) == 3, f"VERSION: {VERSION!r} is not MAJOR.MINOR.PATCH"


def test_pyproject_reads_the_version_file() -> None:
    pyproject = tomllib.loads((REPO / "pyproject.toml").read_text())
    project = pyproject["project"]
    assert "version" not in project, "pyproject.toml: a literal version; it comes from VERSION"
    assert "version" in project.get("dynamic", []), "pyproject.toml: version is not dynamic"
    source = pyproject["tool"]["setuptools"]["dynamic"]["version"]
    assert source in ({"file": "VERSION"}, {"file": ["VERSION"]}), source


def test_fusesoc_core_has_the_version() -> None:
    core_text = (REPO / "fastnms.core").read_text()
    assert yaml.safe_load(core_text)["name"] == f"::fastnms:{VERSION}"
    makefile = (REPO / "Makefile").read_text()
    used = re.findall(r"::fastnms:([\w.]+)", core_text + makefile)
    assert used and set(used) == {VERSION}, f"fastnms.core and Makefile name {sorted(set(used))}"


def test_vivado_ip_has_the_major_minor() -> None:
    common = (REPO / "vivado" / "fastnms_common.tcl").read_text()
    assert re.search(r"^\s*variable version\s+(\S+)", common, re.M).group(1) == IP_VERSION
    texts = [p.read_text() for p in sorted((REPO / "vivado").glob("*.tcl"))]
    texts += [(REPO / "vivado" / "README.md").read_text(), (REPO / "README.md").read_text()]
    vlnvs = {v for t in texts for v in re.findall(r"fastnms:vision:fastnms_axi:([\d.]+\d)", t)}
    zips = {v for t in texts for v in re.findall(r"fastnms_vision_fastnms_axi_([\d.]+\d)\.zip", t)}
    assert vlnvs <= {IP_VERSION} and zips <= {IP_VERSION}, f"IP versions written: {vlnvs | zips}"


def test_register_map_version_is_the_version() -> None:
    regmap = tomllib.loads((REPO / "rtl" / "top" / "fastnms_regs.toml").read_text())
    assert tuple(regmap["map"]["version"]) == PARTS, regmap["map"]["version"]
    (register,) = [r for r in regmap["registers"] if r["name"] == "VERSION"]
    resets = {f["name"]: f["reset"] for f in register["fields"]}
    assert (resets["MAJOR"], resets["MINOR"], resets["PATCH"]) == PARTS, resets
    # What `make regmap` generated from it (flows/regmap/test_regmap.py checks the rest).
    from fastnms.sim import regs

    assert regs.MAP_VERSION == PARTS
    header = (REPO / "sw" / "fastnms_regs.h").read_text()
    assert f'#define FASTNMS_VERSION_STRING "{VERSION}"' in header


def test_changelog_has_a_section_for_the_version() -> None:
    changelog = (REPO / "CHANGELOG.md").read_text()
    assert re.search(rf"^## \[{re.escape(VERSION)}\]", changelog, re.M), (
        f"CHANGELOG.md has no `## [{VERSION}]` section"
    )
