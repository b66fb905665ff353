"""Running the RTL top (fastnms_axi) under GHDL on one image, for `fastnms sim` and
`fastnms compare`.

The simulator runs sim/frame_tb.py (cocotb + cocotbext-axi), so this needs the source
tree (rtl/ beside sim/) and GHDL; the build goes to build/sim/ and is reused between
runs with the same score and NMS.
"""

from __future__ import annotations

import json
import tempfile
import threading
import time
from collections.abc import Callable
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from .ghdl import BUILD, build_and_run
from .sources import RTL

# The largest frame the simulated IP is built for (its MAX_WIDTH, MAX_HEIGHT).
MAX_WIDTH = 1920
MAX_HEIGHT = 1080
MIN_SIZE = 7


class SimError(Exception):
    """The simulation could not run or did not finish; the message says where the log is."""


@dataclass
class SimResult:
    records: np.ndarray  # (N, 3) int64: x, y, score, sorted by y then x
    cycles: int  # first input beat accepted to the frame's last record, inclusive
    wall_seconds: float


def check_size(img: np.ndarray) -> str | None:
    """Why the simulated IP cannot take this image, or None."""
    h, w = img.shape
    if w < MIN_SIZE or h < MIN_SIZE:
        return f"image is {w}x{h}; the IP takes frames from {MIN_SIZE}x{MIN_SIZE}"
    if w > MAX_WIDTH or h > MAX_HEIGHT:
        return f"image is {w}x{h}; the simulated IP is built for at most {MAX_WIDTH}x{MAX_HEIGHT}"
    return None


def run_rtl(
    img: np.ndarray,
    threshold: int,
    score: str,
    nms: str,
    progress: Callable[[int, int, float], None] | None = None,
) -> SimResult:
    """Simulate fastnms_axi on `img`; `progress(rows_in, rows, seconds)` is called about
    once a second while the frame goes in."""
    if not RTL.is_dir():
        raise SimError(f"the RTL is not beside {Path(__file__).parent} (needs the source tree)")
    generics = {"MAX_WIDTH": MAX_WIDTH, "MAX_HEIGHT": MAX_HEIGHT, "SCORE": score, "NMS": nms}
    build_dir = BUILD / f"fastnms_axi-cli-{score}-{nms}"
    build_dir.mkdir(parents=True, exist_ok=True)
    with tempfile.TemporaryDirectory(dir=build_dir) as tmp:
        work = Path(tmp)
        np.save(work / "image.npy", np.ascontiguousarray(img, dtype=np.uint8))
        out, progress_file, log = work / "result.json", work / "progress", build_dir / "sim.log"
        start = time.perf_counter()
        failure: list[BaseException] = []

        def simulate() -> None:
            try:
                tests, failed = build_and_run(
                    "fastnms_axi",
                    "fastnms.sim.frame_tb",
                    generics,
                    build_dir=build_dir,
                    test_dir=work,
                    plusargs=["--ieee-asserts=disable-at-0"],
                    extra_env={
                        "SIM_GENERICS": repr(generics),
                        "SIM_IMAGE": str(work / "image.npy"),
                        "SIM_THRESHOLD": str(threshold),
                        "SIM_OUT": str(out),
                        "SIM_PROGRESS": str(progress_file),
                    },
                    log_file=log,
                )
                if tests == 0 or failed:
                    failure.append(SimError("the cocotb module failed"))
            except BaseException as e:  # reported by the caller's thread
                failure.append(e)

        thread = threading.Thread(target=simulate, daemon=True)
        thread.start()
        while thread.is_alive():
            thread.join(1.0)
            if progress is not None and progress_file.exists():
                try:
                    rows_in, rows = (int(v) for v in progress_file.read_text().split())
                except ValueError:  # caught while being rewritten
                    continue
                progress(rows_in, rows, time.perf_counter() - start)
        wall = time.perf_counter() - start
        if failure or not out.exists():
            raise SimError(f"the simulation failed; see {log}")
        result = json.loads(out.read_text())
    records = np.array(result["records"], dtype=np.int64).reshape(-1, 3)
    records = records[np.lexsort((records[:, 0], records[:, 1]))]
    return SimResult(records, int(result["cycles"]), wall)
