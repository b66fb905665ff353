"""The package `fastnms` as installed: the golden model's public names, and the
dependencies between its parts (the model is pure; the simulation driver does
not reach into the testbenches or the flows)."""

from __future__ import annotations

import ast
from pathlib import Path

import fastnms.golden as golden_pkg
import fastnms.sim as sim_pkg
import pytest


def test_package_reexports_public_api():
    import fastnms.golden as fastnms
    from fastnms.golden import fast, image, model, nms

    assert fastnms.detect is model.detect and fastnms.fast_maps is fast.fast_maps
    assert fastnms.nms_region is nms.nms_region and fastnms.load_grey is image.load_grey
    assert fastnms.SCORES == ("opencv", "sad")
    assert fastnms.NMS_MODES == ("none", "3x3", "region4", "region8")
    assert len(fastnms.CIRCLE_OFFSETS) == 16


def imported_modules(folder: Path) -> dict[str, set[str]]:
    """For each .py file of `folder`, the top-level names of the absolute imports
    it makes (`fastnms.sim` counts as `fastnms.sim`)."""
    out = {}
    for path in sorted(folder.glob("*.py")):
        names = set()
        for node in ast.walk(ast.parse(path.read_text())):
            if isinstance(node, ast.Import):
                names |= {a.name for a in node.names}
            elif isinstance(node, ast.ImportFrom) and node.level == 0 and node.module:
                names.add(node.module)
        out[path.name] = {
            ".".join(n.split(".")[:2]) if n.startswith("fastnms") else n.split(".")[0]
            for n in names
        }
    return out


@pytest.mark.parametrize(
    ("package", "allowed"),
    [
        # The contract: numpy, OpenCV and the standard library, nothing of ours.
        (golden_pkg, {"numpy", "cv2"}),
        # The simulation driver: the simulator's libraries, the model, itself.
        (
            sim_pkg,
            # (cv2: detect_and_compute returns OpenCV's own types.)
            {
                "numpy",
                "cv2",
                "cocotb",
                "cocotbext",
                "cocotb_tools",
                "fastnms.golden",
                "fastnms.sim",
            },
        ),
    ],
    ids=["golden", "sim"],
)
def test_package_dependencies(package, allowed):
    import sys

    folder = Path(package.__file__).parent
    for name, imports in imported_modules(folder).items():
        ours = {i for i in imports if i not in sys.stdlib_module_names and i != "__future__"}
        assert ours <= allowed, f"{folder.name}/{name} imports {sorted(ours - allowed)}"
