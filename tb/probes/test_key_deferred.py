"""pytest entry: the deferred-select synthesis probes (issue 37) simulated against models
that compare the keys themselves (their depth is pinned by
flows/synth/test_probes_deferred.py)."""

import pytest

from flows.synth.synth import PROBES
from tb.harness import run_cocotb


@pytest.mark.parametrize(("key_bits", "lag"), [(34, 2), (34, 1), (5, 2)])
def test_key_deferred_chain(request, key_bits, lag):
    run_cocotb(
        "key_deferred_chain",
        "key_deferred_tb",
        {"KEY_BITS": key_bits, "LAG": lag},
        testcase="chain_random",
        name=request.node.nodeid,
        extra_sources=(PROBES / "key_deferred_chain.vhd",),
    )


@pytest.mark.parametrize("gated_flags", [True, False])
def test_key_deferred(request, gated_flags):
    run_cocotb(
        "key_deferred",
        "key_deferred_tb",
        {"SCORE_BITS": 12, "POS_BITS": 22, "GATED_FLAGS": gated_flags},
        testcase="key_path_random",
        name=request.node.nodeid,
        extra_sources=(PROBES / "key_deferred.vhd",),
    )
