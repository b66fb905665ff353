"""The region NMS's step model (golden/region_stream.py) against the golden rule
(golden/nms.py::nms_region): same records on random, adversarial and hand-made maps, with
random input gaps and output stalls; its stack never deeper than its bound (reached by
nested arches); and one clock per pixel whatever the content."""

from __future__ import annotations

import numpy as np
import pytest
from fastnms.golden.nms import nms_region
from fastnms.golden.region_stream import RegionStream, stack_depth
from fastnms.testing.regions import SHAPES, comb, grid, nested_arches, serpentine, square_spiral


def run(frames, connectivity, max_width=None, **timing):
    model = RegionStream(connectivity, max_width or max(c.shape[1] for c, _ in frames))
    per_frame, eof_clocks = model.run(frames, **timing)
    for i, ((corner, score), got) in enumerate(zip(frames, per_frame, strict=True)):
        want = sorted(map(tuple, nms_region(corner, score, connectivity, with_area=True).tolist()))
        assert sorted(got) == want, f"frame {i} ({corner.shape[1]}x{corner.shape[0]})"
    return model, eof_clocks


def hard_maps(width: int, rng: np.random.Generator) -> list[np.ndarray]:
    h = 14
    yy, xx = np.indices((h, width))
    teeth = comb(h, width)
    diagonal = ((xx + yy) % 3) == 0
    return [
        rng.random((h, width)) < 0.5,
        rng.random((h, width)) < 0.9,
        (xx + yy) % 2 == 0,
        ((xx // 2 + yy // 2) % 2) == 0,
        teeth,
        teeth[::-1].copy(),
        diagonal,
        serpentine(h, width),
        np.ones((h, width), dtype=bool),
        nested_arches(width),
    ]


@pytest.mark.parametrize("connectivity", [4, 8])
def test_hand_made_shapes(connectivity):
    for name, (text, *_) in SHAPES.items():
        corner, score = grid(text)
        if corner.shape[1] >= 3:
            run([(corner, score)], connectivity)
        else:
            print("skipped (narrower than 3):", name)


@pytest.mark.parametrize("connectivity", [4, 8])
def test_random_frames_back_to_back_with_gaps_and_stalls(connectivity, rng):
    for trial in range(150):
        frames = []
        for _ in range(int(rng.integers(1, 4))):
            h, w = int(rng.integers(1, 12)), int(rng.integers(3, 24))
            corner = rng.random((h, w)) < rng.random()
            frames.append((corner, rng.integers(0, 4, (h, w))))
        gaps = (lambda _c: rng.random() < 0.7) if trial % 2 else None
        stalls = (lambda _c: rng.random() < 0.5) if trial % 3 == 0 else None
        run(frames, connectivity, in_valid=gaps, out_ready=stalls)


@pytest.mark.parametrize("connectivity", [4, 8])
def test_hard_content(connectivity, rng):
    for width in (3, 4, 5, 17, 64, 65):
        for corner in hard_maps(width, rng):
            run([(corner, rng.integers(0, 3, corner.shape))], connectivity)
    spiral = square_spiral(33)
    run([(spiral, rng.integers(0, 9, spiral.shape))], connectivity)


@pytest.mark.parametrize("connectivity", [pytest.param(4, marks=pytest.mark.slow), 8])
def test_stack_bound_is_reached_and_holds(connectivity, rng):
    for width in (5, 17, 65, 1920):
        corner = nested_arches(width)
        model, _ = run([(corner, rng.integers(0, 9, corner.shape))], connectivity)
        # The arches reach (W + 3) // 4, the bound itself when (W + 1) % 4 is 2.
        assert (width + 3) // 4 == model.stats.max_depth <= stack_depth(width)


@pytest.mark.parametrize("connectivity", [4, 8])
def test_one_clock_per_pixel_whatever_the_content(connectivity, rng):
    """Back to back, the end-of-frame beats are exactly W x H clocks apart, and the last
    one W + 1 clocks after the last pixel's (the flush of the last row, then the beat)."""
    for corner in hard_maps(48, rng):
        h, w = corner.shape
        frames = [(corner, rng.integers(0, 3, corner.shape))] * 3
        model, eofs = run(frames, connectivity, out_depth=8)
        assert np.diff(eofs).tolist() == [w * h] * 2
        assert eofs[-1] == 3 * w * h + w + 1


@pytest.mark.parametrize("connectivity", [4, 8])
def test_where_full_key_merges_chain(connectivity, rng):
    """A full-key merge (two classes) whose operand the previous column's full-key merge made:
    under 4-connectivity only at a row's column 0 (the class finalized at the previous row's
    last column, pushed again), under 8-connectivity also inside a row (a diagonal contact
    whose class is detached by its pop, then the next run's push). fastnms_nms_region.md,
    Limits, explains what this means for a comparison in a pipeline stage of its own."""
    col0 = in_row = 0
    for width in (5, 17, 64):
        for corner in hard_maps(width, rng) + [rng.random((14, width)) < p for p in (0.3, 0.6)]:
            model, _ = run([(corner, rng.integers(0, 3, corner.shape))], connectivity)
            col0 += model.stats.chained_merges_col0
            in_row += model.stats.chained_merges_in_row
    print(f"region{connectivity}: chained full-key merges at column 0 {col0}, in a row {in_row}")
    assert col0 > 0
    assert (in_row > 0) == (connectivity == 8)
    # The smallest case inside a row: a run starts at x under the gap between two runs above;
    # at x it touches the left one diagonally, which pops, at x + 1 the right one.
    corner, score = grid(
        """
        1 . 1
        . 1 1
        """
    )
    model, _ = run([(corner, score)], connectivity)
    assert model.stats.chained_merges_in_row == (connectivity == 8)
