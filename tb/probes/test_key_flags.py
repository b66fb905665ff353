"""pytest entry: the key_flags synthesis probe simulated against a model that compares
the keys themselves (its depth is pinned by flows/synth/test_synth.py)."""

import pytest

from flows.synth.synth import PROBES
from tb.harness import run_cocotb


@pytest.mark.parametrize("decided_ahead", [False, True])
@pytest.mark.parametrize("pixel_ahead", [False, True])
def test_key_flags(request, decided_ahead, pixel_ahead):
    generics = {
        "SCORE_BITS": 12,
        "POS_BITS": 22,
        "DECIDED_AHEAD": decided_ahead,
        "PIXEL_AHEAD": pixel_ahead,
    }
    run_cocotb(
        "key_flags",
        "key_flags_tb",
        generics,
        name=request.node.nodeid,
        extra_sources=(PROBES / "key_flags.vhd",),
    )
