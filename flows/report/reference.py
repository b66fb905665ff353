"""The published figures and the targets of docs/results.md, read from
reference.toml beside this file (the data; this module only names it)."""

from __future__ import annotations

import tomllib
from pathlib import Path

DATA = tomllib.loads(Path(__file__).with_name("reference.toml").read_text())

PAPER: dict = DATA["paper"]
AMD: dict = DATA["amd"]
AMD_8PPC: dict = DATA["amd_8ppc"]
XC7Z020: dict = DATA["xc7z020"]
ORB_ANCHORS: list[dict] = DATA["orb_anchors"]
TARGETS: dict[str, dict] = DATA["targets"]

_UHD = TARGETS["uhd60-fmax"]
# Pixels per second of the frame rate the PPC rows aim at, in millions, and the
# clock it needs at its pixels per clock.
UHD60_MPIXELS = _UHD["width"] * _UHD["height"] * _UHD["fps"] / 1e6
UHD60_MHZ = UHD60_MPIXELS / _UHD["ppc"]


def limit(key: str) -> float:
    """A target's limit (the uhd60-fmax target's is the clock the frame rate needs)."""
    return UHD60_MHZ if key == "uhd60-fmax" else TARGETS[key]["limit"]
