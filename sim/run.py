"""Running the RTL top (fastnms_axi) on frames, for `fastnms sim`, `fastnms compare`
and the bench, with either engine:

- "verilator" (default): the netlist GHDL synthesizes, compiled by Verilator and
  driven from C++ (sim/verilator.py); about a million clocks per second.
- "cocotb": the RTL under GHDL, driven by cocotb and cocotbext-axi
  (sim/frame_tb.py); a few thousand clocks per second.

Both send the frames back to back (the next frame's size and threshold written
over AXI4-Lite once the previous one's first line is in), count clocks the same way and
draw the same seeded idle and stall patterns (sim/timing.py), so they give the
same records and the same clock counts. Both need the source tree (rtl/).
"""

from __future__ import annotations

import json
import tempfile
import threading
import time
from collections.abc import Callable, Sequence
from dataclasses import dataclass, field
from pathlib import Path

import cv2
import numpy as np
from fastnms.golden.nms import AREA_MAX
from fastnms.golden.orb import PATCH_SIZE

from . import regs, verilator
from .ghdl import BUILD, build_and_run
from .records import decode_records
from .sources import RTL
from .timing import Timing

# The sizes the command line builds the simulated IP for (its MAX_WIDTH, MAX_HEIGHT): the
# first that holds every frame given, so full-HD frames keep the smaller, faster build.
BUILD_SIZES: tuple[tuple[int, int], ...] = ((1920, 1080), (3840, 2160))
MAX_WIDTH, MAX_HEIGHT = BUILD_SIZES[0]  # the default build
LARGEST_WIDTH, LARGEST_HEIGHT = BUILD_SIZES[-1]
MIN_SIZE = 7
ENGINES = ("verilator", "cocotb")
# The largest ORB cell of the command line's ORB builds (their ORB_MAX_CELL): ORB-SLAM's
# cells are about 30 pixels; each doubling doubles the rows the core keeps.
ORB_MAX_CELL = 32
# The STATUS bits that flag malformed video.
MALFORMED = ("EOL_EARLY", "EOL_LATE", "SOF_MISSING", "SOF_EARLY")


class SimError(Exception):
    """The simulation could not run or did not finish; the message says why or where the log is."""


@dataclass
class FrameResult:
    width: int
    height: int
    threshold: int
    records: np.ndarray  # (N, 3) int64: x, y, score, sorted by y then x
    words: np.ndarray  # uint64: the frame's raw records (tdata of m_axis_corners), in output order
    cycles: int  # the frame's first input beat accepted to its last record, inclusive
    input_stalls: int  # clocks with video tvalid high and tready low, during this frame
    # The clock numbers of the frame's first and last input beats and of its last
    # record, for the bench's frame intervals and latencies. Each engine counts
    # from its own origin: only differences compare across engines.
    first_pixel: int
    last_pixel: int
    last_record: int
    # The clock of each word of `words` (its handshake), on the same origin.
    word_clocks: np.ndarray = field(default_factory=lambda: np.zeros(0, np.int64))
    # Per record in `records`' order: its AREA, the region's corner pixels (saturating at
    # 2047) with the region NMS, 0 with the others.
    areas: np.ndarray = field(default_factory=lambda: np.zeros(0, np.int64))
    # With ORB (record format 2), per record in `records`' order: the angle's float32
    # bits and the 32 descriptor bytes; empty otherwise.
    angle_bits: np.ndarray = field(default_factory=lambda: np.zeros(0, np.uint32))
    descriptors: np.ndarray = field(default_factory=lambda: np.zeros((0, 32), np.uint8))


@dataclass
class SimResult:
    frames: list[FrameResult]
    cycles: int  # first input beat of the first frame to the last record of the last
    input_stalls: int
    wall_seconds: float  # the simulation, without the build
    engine: str
    build_seconds: float | None = None  # set when this call built the engine
    status: int | None = None  # STATUS read after the last frame (fast engine)
    extra: dict = field(default_factory=dict)

    @property
    def records(self) -> np.ndarray:
        """The first frame's records (the only frame's, for one image)."""
        return self.frames[0].records


def check_size(
    img: np.ndarray, ppc: int = 1, max_width: int = MAX_WIDTH, max_height: int = MAX_HEIGHT
) -> str | None:
    """Why the simulated IP (PPC pixels per clock, built for max_width x
    max_height) cannot take this image, or None."""
    h, w = img.shape
    min_width = MIN_SIZE if ppc == 1 else 8
    if w < min_width or h < MIN_SIZE:
        return f"image is {w}x{h}; the IP takes frames from {min_width}x{MIN_SIZE}"
    if w > max_width or h > max_height:
        return f"image is {w}x{h}; the simulated IP is built for at most {max_width}x{max_height}"
    if w % ppc:
        return f"image is {w} pixels wide: with {ppc} pixels per clock, not a multiple of {ppc}"
    return None


def decode_frame(words: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
    """One frame's record words (either record format) as (records (N, 3) int64, areas
    (N,) int64, angle bits (N,) uint32, descriptors (N, 32) uint8), sorted by y then x;
    the last two are empty without ORB."""
    frames = decode_records(int(w) for w in np.asarray(words, dtype=np.uint64))
    if len(frames) != 1 or not frames[0].complete or frames[0].malformed:
        raise SimError(f"a frame's records do not decode as one frame: {len(frames)} frames")
    frame = frames[0]
    recs = np.array(frame.corners, dtype=np.int64).reshape(-1, 3)
    order = np.lexsort((recs[:, 0], recs[:, 1]))
    areas = np.array(frame.areas, dtype=np.int64)
    angles = np.array(frame.angle_bits, dtype=np.uint32)
    descriptors = np.frombuffer(b"".join(frame.descriptors), np.uint8).reshape(-1, 32)
    if frame.orb:
        return recs[order], areas[order], angles[order], descriptors[order]
    return recs[order], areas[order], angles[:0], descriptors[:0]


def build_size(shapes: Sequence[tuple[int, int]]) -> tuple[int, int]:
    """(MAX_WIDTH, MAX_HEIGHT): the first of BUILD_SIZES that holds every (height, width)."""
    for width, height in BUILD_SIZES:
        if all(w <= width and h <= height for h, w in shapes):
            return width, height
    return BUILD_SIZES[-1]


def generics_for(
    score: str,
    nms: str,
    ppc: int = 1,
    size: tuple[int, int] = (MAX_WIDTH, MAX_HEIGHT),
    budget: bool = False,
    orb: bool = False,
) -> dict[str, object]:
    """The top's generics for the CLI's builds (PPC only when above 1,
    MAX_PER_CELL = 15 only with `budget` or `orb`, DESCRIPTOR and ORB_MAX_CELL only
    with `orb`, so that the other builds keep their names)."""
    generics: dict[str, object] = {
        "MAX_WIDTH": size[0],
        "MAX_HEIGHT": size[1],
        "SCORE": score,
        "NMS": nms,
    }
    if ppc != 1:
        generics["PPC"] = ppc
    if budget or orb:
        generics["MAX_PER_CELL"] = 15
    if orb:
        generics["DESCRIPTOR"] = "orb"
        generics["ORB_MAX_CELL"] = ORB_MAX_CELL
    return generics


# The ORB engine's clocks per keypoint in the top (512 / ORB_LANES, rtl/common/
# fastnms_pkg.vhd): at one pixel per clock it keeps up with CELL * CELL / 64 per cell.
ORB_KEYPOINT_CLOCKS = 64


def budget_in_effect(cell: int, per_cell: int, generics: dict[str, object]) -> tuple[int, int]:
    """The (CELL, K) a frame uses after (cell, per_cell) is written to BUDGET of a
    build with `generics`, cell a power of two in 16 .. 256: K at most MAX_PER_CELL;
    with DESCRIPTOR "orb", CELL at most ORB_MAX_CELL, then K at most the ORB engine's
    rate at that CELL, CELL * CELL / 64 (4 at CELL 16; docs/registers.md, BUDGET)."""
    k = min(per_cell, int(generics.get("MAX_PER_CELL", 0)))
    if generics.get("DESCRIPTOR", "none") == "orb":
        cell = min(cell, int(generics.get("ORB_MAX_CELL", 16)))
        k = min(k, cell * cell // ORB_KEYPOINT_CLOCKS)
    return cell, k


def run_rtl(
    frames: Sequence[tuple[np.ndarray, int]],
    score: str,
    nms: str,
    *,
    engine: str = "verilator",
    timing: Timing = Timing(),  # noqa: B008 (frozen: one shared default is safe)
    progress: Callable[[int, int, float], None] | None = None,
    announce: Callable[[str], None] | None = None,
    generics: dict[str, object] | None = None,
    power_up_seed: int | None = None,
    budget: tuple[int, int] | None = None,
    min_area: int | None = None,
) -> SimResult:
    """Simulate fastnms_axi on `frames` (image, threshold), sent back to back.
    `progress(pixels_in, pixels, seconds)` is called about once a second;
    `announce(text)` before a build of the fast engine. `generics` overrides
    the build (default: MAX_WIDTH x MAX_HEIGHT with score and nms). `budget`
    (cell, per_cell) is written to BUDGET with every frame's registers (the
    build needs MAX_PER_CELL > 0: generics_for(..., budget=True)). `min_area`
    (0 .. 2047) is written to MIN_AREA with every frame's registers (the region
    NMS drops the regions of fewer corner pixels; the others ignore it); None:
    MIN_AREA is not written (its reset value 0 keeps every region)."""
    if not RTL.is_dir():
        raise SimError(f"the RTL is not beside {Path(__file__).parent} (needs the source tree)")
    if not frames:
        raise SimError("no frame to simulate")
    generics = generics or generics_for(score, nms, budget=budget is not None)
    if budget is not None and not int(generics.get("MAX_PER_CELL", 0)):
        raise SimError("a budget needs a build with the budget (MAX_PER_CELL > 0)")
    if min_area is not None and (
        isinstance(min_area, bool)
        or not isinstance(min_area, int | np.integer)
        or not 0 <= min_area <= AREA_MAX
    ):
        raise SimError(f"min_area must be an integer in 0..{AREA_MAX}, got {min_area!r}")
    min_area = None if min_area is None else int(min_area)
    if engine == "verilator":
        return _run_verilator(
            frames, generics, timing, progress, announce, power_up_seed, budget, min_area
        )
    if engine == "cocotb":
        if timing.hblank or timing.vblank:
            raise SimError("blanking (hblank, vblank) needs the verilator engine")
        return _run_cocotb(frames, generics, timing, progress, budget, min_area)
    raise SimError(f"unknown engine {engine!r}; choose from {', '.join(ENGINES)}")


def _frame_results(frames, raw_frames) -> list[FrameResult]:
    results = []
    for (img, threshold), raw in zip(frames, raw_frames, strict=True):
        records, areas, angle_bits, descriptors = decode_frame(raw.words)
        results.append(
            FrameResult(
                width=img.shape[1],
                height=img.shape[0],
                threshold=threshold,
                records=records,
                words=raw.words,
                cycles=raw.last_record - raw.first_pixel + 1,
                input_stalls=raw.input_stalls,
                first_pixel=raw.first_pixel,
                last_pixel=raw.last_pixel,
                last_record=raw.last_record,
                word_clocks=raw.word_clocks,
                areas=areas,
                angle_bits=angle_bits,
                descriptors=descriptors,
            )
        )
    return results


def _run_verilator(
    frames, generics, timing, progress, announce, power_up_seed, budget, min_area
) -> SimResult:
    try:
        exe, build_seconds = verilator.build(generics, announce)
    except verilator.EngineError as e:
        raise SimError(str(e)) from None
    start = time.perf_counter()

    def report(pixels_in: int, pixels: int) -> None:
        if progress is not None:
            progress(pixels_in, pixels, time.perf_counter() - start)

    try:
        ppc = int(generics.get("PPC", 1))
        raw = verilator.run(exe, frames, timing, report, power_up_seed, ppc, budget, min_area)
    except verilator.EngineError as e:
        raise SimError(f"the fast engine stopped: {e}") from None
    # The drivers send well-formed video: a malformed-frame flag or a frame
    # count off by one is the IP's fault, never to be passed over.
    flagged = [name for name in MALFORMED if getattr(regs, f"STATUS_{name}").get(raw.status)]
    if flagged or raw.frame_count != len(frames):
        raise SimError(
            f"the IP flagged well-formed video ({', '.join(flagged) or 'no flag'}; "
            f"FRAME_COUNT {raw.frame_count} after {len(frames)} frames)"
        )
    return SimResult(
        frames=_frame_results(frames, raw.frames),
        cycles=raw.cycles,
        input_stalls=raw.input_stalls,
        wall_seconds=time.perf_counter() - start,
        engine="verilator",
        build_seconds=build_seconds,
        status=raw.status,
        extra={"frame_count": raw.frame_count},
    )


def _run_cocotb(frames, generics, timing, progress, budget, min_area) -> SimResult:
    name = "-".join(f"{k}{v}" for k, v in sorted(generics.items()))
    run_dir = BUILD / f"fastnms_axi-cli-{name}"
    run_dir.mkdir(parents=True, exist_ok=True)
    with tempfile.TemporaryDirectory(dir=run_dir) as tmp:
        work = Path(tmp)
        np.savez(work / "frames.npz", *[np.ascontiguousarray(img, np.uint8) for img, _ in frames])
        out, progress_file, log = work / "result.json", work / "progress", run_dir / "sim.log"
        start = time.perf_counter()
        failure: list[BaseException] = []

        def simulate() -> None:
            try:
                tests, failed = build_and_run(
                    "fastnms_axi",
                    "fastnms.sim.frame_tb",
                    generics,
                    test_dir=work,
                    # The line buffers start undefined (as BRAMs do not in
                    # hardware): numeric_std's warnings about them are noise.
                    plusargs=["--ieee-asserts=disable"],
                    extra_env={
                        "SIM_GENERICS": repr(generics),
                        "SIM_FRAMES": str(work / "frames.npz"),
                        "SIM_THRESHOLDS": " ".join(str(t) for _, t in frames),
                        "SIM_TIMING": json.dumps(timing.as_dict()),
                        "SIM_OUT": str(out),
                        "SIM_PROGRESS": str(progress_file),
                        "SIM_BUDGET": "" if budget is None else f"{budget[0]} {budget[1]}",
                        "SIM_MIN_AREA": "" if min_area is None else str(min_area),
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
                    pixels_in, pixels = (int(v) for v in progress_file.read_text().split())
                except ValueError:  # caught while being rewritten
                    continue
                progress(pixels_in, pixels, time.perf_counter() - start)
        wall = time.perf_counter() - start
        if failure or not out.exists():
            raise SimError(f"the simulation failed; see {log}")
        result = json.loads(out.read_text())
    raw = [
        verilator.RawFrame(
            f["first_pixel"],
            f["last_pixel"],
            f["last_record"],
            np.array(f["words"], dtype=np.uint64),
            f["input_stalls"],
            np.array(f["word_clocks"], dtype=np.int64),
        )
        for f in result["frames"]
    ]
    return SimResult(
        frames=_frame_results(frames, raw),
        cycles=raw[-1].last_record - raw[0].first_pixel + 1,
        input_stalls=result["input_stalls"],
        wall_seconds=wall,
        engine="cocotb",
    )


def detect_and_compute(
    img: np.ndarray,
    threshold: int = 20,
    score: str = "opencv",
    nms: str = "3x3",
    cell: int = 16,
    per_cell: int = 4,
    *,
    engine: str = "verilator",
    announce: Callable[[str], None] | None = None,
) -> tuple[tuple[cv2.KeyPoint, ...], np.ndarray]:
    """The RTL's ORB keypoints and descriptors on one image (fastnms_axi with DESCRIPTOR
    "orb", simulated), in the types fastnms.golden.orb.detect_and_compute gives: a tuple
    of cv2.KeyPoint (pt, response = score, angle, size 31, octave 0) and an (N, 32) uint8
    array, sorted by y then x; at most per_cell keypoints per cell x cell square. The
    hardware needs the budget (per_cell 1..15; with 0 it may drop keypoints) and a cell
    of 16 or ORB_MAX_CELL; NMS "3x3" or "none"."""
    if nms not in ("3x3", "none"):
        raise SimError(f"ORB in the RTL takes NMS 3x3 or none, not {nms!r}")
    if not 1 <= per_cell <= 15:
        raise SimError(f"ORB in the RTL needs a budget: per_cell 1..15, got {per_cell}")
    if cell not in (16, ORB_MAX_CELL):
        raise SimError(f"ORB in the simulated RTL takes cells of 16 or {ORB_MAX_CELL}, got {cell}")
    problem = check_size(img, 1, LARGEST_WIDTH, LARGEST_HEIGHT)
    if problem:
        raise SimError(problem)
    generics = generics_for(score, nms, size=build_size([img.shape]), orb=True)
    result = run_rtl(
        [(img, threshold)],
        score,
        nms,
        engine=engine,
        generics=generics,
        budget=(cell, per_cell),
        announce=announce,
    )
    frame = result.frames[0]
    angles = frame.angle_bits.view(np.float32).tolist()
    keypoints = tuple(
        cv2.KeyPoint(float(x), float(y), float(PATCH_SIZE), float(a), float(s), 0, -1)
        for (x, y, s), a in zip(frame.records.tolist(), angles, strict=True)
    )
    return keypoints, frame.descriptors
