"""The paper's region filtering through the model's entry point: detect(..., min_area,
with_area) with the region NMS, on real photographs and on synthetic images, against
connected components of the corner map that OpenCV labels (an independent reference):
one record per region, its AREA the region's corner pixels saturated at 2047, and
min_area N keeping exactly the regions of N pixels or more. The other NMS: no regions,
AREA 0, min_area above 1 refused."""

from __future__ import annotations

import cv2
import numpy as np
import pytest
from fastnms.golden.fast import fast_maps
from fastnms.golden.model import NMS_MODES, SCORES, detect
from fastnms.golden.nms import AREA_MAX
from fastnms.testing import images as testimages

REGION = ("region4", "region8")


def reference_areas(img: np.ndarray, threshold: int, score: str, nms: str) -> tuple[int, dict]:
    """(the number of regions, {(x, y): the area of the region holding pixel (x, y)})
    from cv2.connectedComponents of the corner map."""
    corner, _ = fast_maps(img, threshold, score)
    count, labels = cv2.connectedComponents(
        corner.astype(np.uint8), connectivity=4 if nms == "region4" else 8, ltype=cv2.CV_32S
    )
    sizes = np.bincount(labels.ravel(), minlength=count)
    ys, xs = np.nonzero(corner)
    return count - 1, {
        (int(x), int(y)): int(sizes[labels[y, x]]) for x, y in zip(xs, ys, strict=True)
    }


def check_areas_and_filter(img: np.ndarray, threshold: int, score: str, nms: str) -> np.ndarray:
    """detect's areas against the reference, and min_area against the areas; returns the
    records with their areas (min_area 0)."""
    every = detect(img, threshold, score, nms, with_area=True)
    assert every.dtype == np.int64 and every.shape[1] == 4
    plain = detect(img, threshold, score, nms)
    assert np.array_equal(every[:, :3], plain), "with_area changes only the fourth column"
    regions, area_at = reference_areas(img, threshold, score, nms)
    assert len(every) == regions, "one record per region"
    want = [min(area_at[(x, y)], AREA_MAX) for x, y, _, _ in every.tolist()]
    assert every[:, 3].tolist() == want
    assert (every[:, 3] >= 1).all()
    top = int(every[:, 3].max()) if len(every) else 0
    for n in sorted({0, 1, 2, 3, 4, 7, top, top + 1, AREA_MAX}):
        if n > AREA_MAX:
            continue
        kept = detect(img, threshold, score, nms, min_area=n, with_area=True)
        assert np.array_equal(kept, every[every[:, 3] >= n]), f"min_area {n}"
        assert np.array_equal(detect(img, threshold, score, nms, min_area=n), kept[:, :3])
    return every


@pytest.mark.parametrize("nms", REGION)
@pytest.mark.parametrize("score", SCORES)
def test_region_areas_on_a_shared_photograph(shared_image, score: str, nms: str):
    """A 160x120 crop of each photograph of ../shared/images (no cases without it)."""
    img = testimages.crop(shared_image, 160, 120)
    every = check_areas_and_filter(img, 20, score, nms)
    assert len(every) > 0 or cv2.meanStdDev(img)[1][0, 0] < 4, "a textured crop has corners"


@pytest.mark.parametrize("nms", REGION)
def test_region_areas_on_a_real_photograph(nms: str):
    """The first real photograph (../shared/images, else scikit-image's), 200x150, at a
    low threshold: regions of many sizes."""
    img = testimages.crop(testimages.real_images()[0], 200, 150)
    every = check_areas_and_filter(img, 8, "opencv", nms)
    assert len(every) > 20 and (every[:, 3] == 1).any() and every[:, 3].max() >= 5


def test_region_areas_on_synthetic_images(rng: np.random.Generator):
    """Isolated bright dots are regions of one pixel, a 2x2 block one region of four;
    min_area 2 drops exactly the dots. Then random images of several kinds."""
    img = np.full((40, 48), 60, dtype=np.uint8)
    dots = [(8, 6), (30, 7), (12, 30), (40, 33)]
    for x, y in dots:
        img[y, x] = 220
    img[18:20, 22:24] = 220
    for nms in REGION:
        every = check_areas_and_filter(img, 30, "opencv", nms)
        by_place = {(x, y): a for x, y, _, a in every.tolist()}
        assert by_place == {**dict.fromkeys(dots, 1), (22, 18): 4}, nms
        kept = detect(img, 30, "opencv", nms, min_area=2, with_area=True)
        assert kept[:, :2].tolist() == [[22, 18]] and kept[:, 3].tolist() == [4]
        assert detect(img, 30, "opencv", nms, min_area=5).shape == (0, 3)
    kinds = [testimages.blurred_noise, testimages.checkerboard, testimages.single_pixels]
    for make in kinds:
        img = make(rng, 64, 48)
        for score in SCORES:
            for nms in REGION:
                for t in (0, 10, 40):
                    check_areas_and_filter(img, t, score, nms)


def test_region_area_saturates_at_2047(rng: np.random.Generator, seed: int):
    """Blurred noise at threshold 0: a region of more than 2047 pixels has AREA 2047,
    and min_area 2047 keeps exactly the regions of 2047 pixels or more."""
    img = testimages.blurred_noise(rng, 160, 120)  # its largest 4-connected region: > 4000
    for nms in REGION:
        every = check_areas_and_filter(img, 0, "opencv", nms)
        _, area_at = reference_areas(img, 0, "opencv", nms)
        places = [(x, y) for x, y, _, _ in every.tolist()]
        assert any(area_at[p] > AREA_MAX for p in places), f"no region that large (seed {seed})"
        kept = detect(img, 0, "opencv", nms, min_area=AREA_MAX, with_area=True)
        want = [p for p in places if area_at[p] >= AREA_MAX]
        assert [(x, y) for x, y, _, _ in kept.tolist()] == want, f"seed {seed}"
        assert (kept[:, 3] == AREA_MAX).all()


@pytest.mark.parametrize("nms", ["none", "3x3"])
def test_other_nms_have_no_area_and_refuse_min_area(nms: str):
    img = testimages.crop(testimages.real_images()[0], 120, 90)
    plain = detect(img, 10, "opencv", nms)
    assert len(plain) > 0
    with_area = detect(img, 10, "opencv", nms, with_area=True)
    assert with_area.shape == (len(plain), 4) and with_area.dtype == np.int64
    assert np.array_equal(with_area[:, :3], plain) and not with_area[:, 3].any()
    for n in (0, 1):  # keep every region: accepted, nothing changes
        assert np.array_equal(detect(img, 10, "opencv", nms, min_area=n), plain)
    for n in (2, 3, AREA_MAX):
        with pytest.raises(ValueError, match="min_area"):
            detect(img, 10, "opencv", nms, min_area=n)


@pytest.mark.parametrize("nms", NMS_MODES)
@pytest.mark.parametrize("bad", [-1, AREA_MAX + 1, 2.0, "3", True, None])
def test_min_area_out_of_range(nms: str, bad):
    img = np.zeros((10, 10), dtype=np.uint8)
    with pytest.raises(ValueError, match="min_area"):
        detect(img, 20, "opencv", nms, min_area=bad)
