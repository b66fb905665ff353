"""pytest fixtures shared by every test of the repository (a plugin: the root conftest.py
loads it).

- Shared images: real photographs in (repo root)/../shared/images, or $FASTNMS_IMAGES
  (fastnms.testing.images.shared_images). The folder is optional: tests that take the
  `shared_image` argument are parametrised over its photographs and simply have no cases
  when it is absent.
- Randomness: one base seed from $FASTNMS_SEED (default DEFAULT_SEED), shown in the pytest
  header; each test's generator is derived from it and the test id, so a failing test
  replays identically alone or under xdist. Tests put the seed in their failure messages.
"""

from __future__ import annotations

import os
import zlib

import cv2
import numpy as np
import pytest

from .images import shared_images, shared_images_folder

DEFAULT_SEED = 20260522
SEED = int(os.environ.get("FASTNMS_SEED", DEFAULT_SEED))


def pytest_report_header(config: pytest.Config) -> list[str]:
    n = len(shared_images())
    return [
        f"fastnms: FASTNMS_SEED={SEED}; shared images: {n} in {shared_images_folder()}",
    ]


def pytest_generate_tests(metafunc: pytest.Metafunc) -> None:
    if "shared_image" in metafunc.fixturenames:
        paths = shared_images()
        metafunc.parametrize("shared_image", paths, ids=[p.name for p in paths])


@pytest.fixture
def seed(request: pytest.FixtureRequest) -> int:
    """A per-test seed derived from the base seed and the test id (stable across runs)."""
    value = SEED ^ zlib.crc32(request.node.nodeid.encode())
    print(f"FASTNMS_SEED={SEED} (test seed {value})")
    return value


@pytest.fixture
def rng(seed: int) -> np.random.Generator:
    return np.random.default_rng(seed)


@pytest.fixture(params=[True, False], ids=["optimized", "plain"])
def cv_optimized(request: pytest.FixtureRequest):
    """Run the test once with OpenCV's optimised dispatch (AVX2 paths) and once without
    (baseline SIMD and scalar code), restoring the previous setting afterwards."""
    previous = cv2.useOptimized()
    cv2.setUseOptimized(request.param)
    try:
        yield request.param
    finally:
        cv2.setUseOptimized(previous)


@pytest.hookimpl(wrapper=True)
def pytest_runtest_makereport(item: pytest.Item, call: pytest.CallInfo):
    """Attach the seed to every failing report of a test that used randomness, so the
    failure can be replayed whatever the -r options."""
    report = yield
    if report.failed and "seed" in getattr(item, "fixturenames", ()):
        report.sections.append(
            ("fastnms seed", f"replay with FASTNMS_SEED={SEED} pytest '{item.nodeid}'")
        )
    return report
