"""`make bench`: measured throughput, latency and simulation speed of the AXI
top (fastnms_axi under GHDL + cocotb, flows/bench/bench_tb.py), the region NMS's
memory against the paper's formula, and the golden model's and OpenCV's time
per frame on this machine. Writes build/bench/summary.json and the bench
section of docs/results.md (flows/report/report.py).

    python -m flows.bench.bench [--width 1920 --height 1080 --frames 3 --jobs 2 ...]

Frames: the largest real photographs (fastnms.testing.images: ../shared/images if
present, else scikit-image's bundled ones), each scaled to cover the frame
with cv2.resize and cropped at its centre; sent back to back with no input
idles and no output back-pressure, every frame's records compared with the
golden model.
"""

from __future__ import annotations

import argparse
import json
import os
import platform
import tempfile
import time
from concurrent.futures import ProcessPoolExecutor
from pathlib import Path

import cv2
import numpy as np
from fastnms.sim.ghdl import BUILD, build_and_run, ghdl_version
from fastnms.sim.sources import REPO
from fastnms.testing import images as testimages

from flows.bench import software
from flows.report import report

BENCH_BUILD = REPO / "build" / "bench"
CONFIGS = [("opencv", "3x3"), ("sad", "region4"), ("opencv", "region8")]
SCORE_BITS = {"opencv": 8, "sad": 12}
WIDTH, HEIGHT = 1920, 1080
FRAMES = 3
THRESHOLD = 20
EVENT_DEPTH = 512  # fastnms_nms_region's default


# ---- frames ----------------------------------------------------------------------


def bench_images(count: int) -> list[Path]:
    """The `count` largest real photographs (by pixels, then by name)."""
    sized = []
    for path in testimages.real_images():
        img = cv2.imread(str(path), cv2.IMREAD_UNCHANGED)
        sized.append((-img.shape[0] * img.shape[1], path.name, path))
    return [p for _, _, p in sorted(sized)[:count]]


def fit(img: np.ndarray, width: int, height: int) -> np.ndarray:
    """Scale `img` to cover width x height (cv2.resize, area when shrinking,
    bilinear when enlarging), then crop the centre."""
    h, w = img.shape
    scale = max(width / w, height / h)
    size = (max(width, round(w * scale)), max(height, round(h * scale)))
    interp = cv2.INTER_AREA if scale < 1 else cv2.INTER_LINEAR
    big = cv2.resize(img, size, interpolation=interp)
    y0, x0 = (size[1] - height) // 2, (size[0] - width) // 2
    return np.ascontiguousarray(big[y0 : y0 + height, x0 : x0 + width])


def bench_frames(width: int, height: int, count: int) -> tuple[np.ndarray, list[str]]:
    """`count` frames (count x height x width, uint8) and the names of their photographs."""
    from fastnms.golden.image import load_grey

    paths = bench_images(count)
    paths = (paths * count)[:count]  # fewer photographs than frames: repeat them
    frames = np.stack([fit(load_grey(p), width, height) for p in paths])
    return frames, [p.name for p in paths]


# ---- region NMS memory -----------------------------------------------------------


def clog2(n: int) -> int:
    """fastnms_pkg.clog2: the bits of an index into n things (at least 1)."""
    bits = 1
    while 2**bits < n:
        bits += 1
    return bits


def bits_for(n: int) -> int:
    """fastnms_pkg.bits_for: the bits that hold the value n itself."""
    return clog2(n + 1)


def region_memory(
    max_width: int, max_height: int, score_bits: int, event_depth: int = EVENT_DEPTH
) -> dict:
    """The region NMS's memories in bits, from its generics, as the RTL sizes
    them (rtl/nms/fastnms_nms_region*.vhd), with the paper's formula and a
    5-line FIFO NMS beside them."""
    labels = max_width // 2 + 3
    label_bits = clog2(labels)
    run_bits = bits_for(max_width // 2 + 1)
    x_bits, y_bits = clog2(max_width), bits_for(max_height)
    key_bits = score_bits + x_bits + y_bits
    event_bits = 6 + 3 * label_bits + score_bits + x_bits + y_bits

    def fifo_words(depth: int) -> int:
        """fastnms_fifo's RAM: DEPTH rounded up to a power of two, at least 4."""
        return 2 ** max(2, clog2(depth))

    rows = [
        ("label line (RAM index)", max_width, label_bits + 1),
        # runs, next and prev each carry a flag bit (runs = 1, has next, has prev).
        ("label tables: region, runs, next, prev", labels, 3 * label_bits + run_bits + 3),
        ("region tables: best key, head, tail (RAM score)", labels, key_bits + 2 * label_bits),
        # Each free list is a fastnms_fifo of LABELS + 2 words.
        ("free lists: labels, regions", 2 * fifo_words(labels + 2), label_bits),
        ("event queue", fifo_words(event_depth), event_bits),
    ]
    breakdown = [{"memory": m, "words": n, "bits_per_word": b, "bits": n * b} for m, n, b in rows]
    paper = (max_width // 2) * (score_bits + x_bits + y_bits + label_bits)
    return {
        "max_width": max_width,
        "max_height": max_height,
        "score_bits": score_bits,
        "labels": labels,
        "label_bits": label_bits,
        "x_bits": x_bits,
        "y_bits": y_bits,
        "event_depth": event_depth,
        "breakdown": breakdown,
        "total_bits": sum(r["bits"] for r in breakdown),
        "paper_formula_bits": paper,
        "paper_formula": f"({max_width}/2) x ({score_bits} + {x_bits} + {y_bits} + {label_bits})",
        "fifo5_bits": 5 * max_width * score_bits,
        "nms_3x3_bits": 2 * max_width * score_bits,
    }


# ---- golden model and OpenCV -------------------------------------------------------


def software_times(frame: np.ndarray, threshold: int) -> list[dict]:
    """Best of 3 wall times of the golden model (the bench's configurations)
    and of cv2.FastFeatureDetector on one frame (flows/bench/software.py's timer)."""
    from fastnms.golden.model import detect

    rows = []
    for score, nms in CONFIGS:
        ms, rec = software.best_ms(lambda s=score, n=nms: detect(frame, threshold, s, n))
        rows.append(
            {
                "what": f"golden {score} + {nms}",
                "ms": ms,
                "corners": len(rec),
                "best_of": software.REPEATS,
            }
        )
    for nonmax in (True, False):
        det = cv2.FastFeatureDetector_create(
            threshold=threshold, nonmaxSuppression=nonmax, type=cv2.FAST_FEATURE_DETECTOR_TYPE_9_16
        )
        ms, kps = software.best_ms(lambda d=det: d.detect(frame))
        label = "opencv + 3x3" if nonmax else "opencv + none"
        rows.append(
            {
                "what": f"cv2.FastFeatureDetector {label}",
                "ms": ms,
                "corners": len(kps),
                "best_of": software.REPEATS,
            }
        )
    return rows


# ---- simulation ------------------------------------------------------------------


def simulate(
    score: str,
    nms: str,
    frames_file: Path,
    count: int,
    threshold: int,
    max_width: int,
    max_height: int,
    check: bool = True,
) -> dict:
    """Run flows/bench/bench_tb.py on fastnms_axi; return its raw figures plus the
    derived ones (clocks per pixel, latencies, pixels per wall second)."""
    generics = {"MAX_WIDTH": max_width, "MAX_HEIGHT": max_height, "SCORE": score, "NMS": nms}
    name = f"bench-{score}-{nms}"
    log = frames_file.parent / f"{name}-{max_width}x{max_height}.log"
    with tempfile.TemporaryDirectory(dir=frames_file.parent) as tmp:
        out = Path(tmp) / "bench.json"
        start = time.perf_counter()
        run_bench(
            generics,
            name,
            log,
            {
                "BENCH_FRAMES": str(frames_file),
                "BENCH_COUNT": str(count),
                "BENCH_THRESHOLD": str(threshold),
                "BENCH_CHECK": "1" if check else "0",
                "BENCH_OUT": str(out),
            },
        )
        run_seconds = time.perf_counter() - start
        raw = json.loads(out.read_text())
    return derive(raw, score, nms, generics, run_seconds)


def run_bench(generics: dict, name: str, log: Path, env: dict[str, str]) -> None:
    """flows/bench/bench_tb.py on fastnms_axi, in the tests' build directory
    (tb/harness.py names it the same way), with two differences from the tests:
    GHDL's numeric_std warnings are off for the whole run (the first rows of
    every line buffer are uninitialised RAM: hundreds of thousands of metavalue
    warnings at 1920 pixels, which cost wall time), and the simulator's output
    goes to `log`."""
    key = "-".join(f"{k}{v}" for k, v in sorted(generics.items()))
    build_dir = BUILD / f"fastnms_axi-{key}"
    tests, failed = build_and_run(
        "fastnms_axi",
        "flows.bench.bench_tb",
        generics,
        build_dir=build_dir,
        test_dir=build_dir / name,
        plusargs=["--ieee-asserts=disable"],
        extra_env={"BENCH_GENERICS": repr(generics), **env},
        seed=1,  # the bench has no random idles or stalls
        log_file=log,
    )
    if tests == 0 or failed:
        raise RuntimeError(f"{name}: the bench failed, see {log}")


def derive(raw: dict, score: str, nms: str, generics: dict, run_seconds: float) -> dict:
    n, pixels = raw["frames"], raw["width"] * raw["height"]
    first, last_in, last_out = raw["first_pixel"], raw["last_pixel"], raw["last_record"]
    intervals = [b - a for a, b in zip(last_out, last_out[1:], strict=False)]
    return {
        "config": f"{score}-{nms}-{raw['width']}x{raw['height']}",
        "score": score,
        "nms": nms,
        "generics": generics,
        **raw,
        # Input side: clocks from the first to the last pixel taken, per pixel.
        "input_clocks_per_pixel": (last_in[-1] - first + 1) / (n * pixels),
        # Output side: clocks between consecutive frames' last records, per pixel.
        "frame_interval_clocks": intervals,
        "steady_clocks_per_pixel": (sum(intervals) / len(intervals) / pixels)
        if intervals
        else None,
        "total_clocks_per_pixel": (last_out[-1] - first + 1) / (n * pixels),
        # From a frame's last pixel in to its last record out.
        "latency_clocks": [o - i for i, o in zip(last_in, last_out, strict=True)],
        "sim_pixels_per_second": n * pixels / raw["wall_seconds"],
        "run_seconds": run_seconds,
    }


def machine() -> dict:
    cpu = platform.processor()
    try:
        for line in Path("/proc/cpuinfo").read_text().splitlines():
            if line.startswith("model name"):
                cpu = line.split(":", 1)[1].strip()
                break
    except OSError:
        pass
    return {
        "cpu": cpu,
        "cores": os.cpu_count(),
        "python": platform.python_version(),
        "opencv": cv2.__version__,
    }


def main(argv: list[str] | None = None) -> None:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--width", type=int, default=WIDTH)
    ap.add_argument("--height", type=int, default=HEIGHT)
    ap.add_argument("--frames", type=int, default=FRAMES)
    ap.add_argument("--threshold", type=int, default=THRESHOLD)
    ap.add_argument("--jobs", type=int, default=int(os.environ.get("JOBS", "2")))
    ap.add_argument("--configs", default=",".join(f"{s}-{n}" for s, n in CONFIGS))
    ap.add_argument("--no-check", action="store_true", help="do not compare with the golden")
    ap.add_argument("--out", type=Path, default=BENCH_BUILD / "summary.json")
    ap.add_argument("--no-report", action="store_true", help="do not rewrite docs/results.md")
    args = ap.parse_args(argv)
    args.out = args.out.resolve()  # the simulator runs in another folder
    configs = [tuple(c.split("-", 1)) for c in args.configs.split(",")]

    start = time.perf_counter()
    load = round(os.getloadavg()[0], 1)
    source = report.source_state()
    args.out.parent.mkdir(parents=True, exist_ok=True)
    frames, sources = bench_frames(args.width, args.height, args.frames)
    frames_file = args.out.parent / f"frames-{args.width}x{args.height}x{args.frames}.npy"
    np.save(frames_file, frames)
    print(f"bench: {args.frames} frames {args.width}x{args.height} from {', '.join(sources)}")

    # The software timings first, alone on the machine.
    software = software_times(frames[0], args.threshold)
    for row in software:
        print(f"bench: {row['what']:<40} {row['ms']:8.1f} ms  {row['corners']} corners")

    sims = []
    with ProcessPoolExecutor(max_workers=max(1, args.jobs)) as pool:
        futures = [
            pool.submit(
                simulate,
                score,
                nms,
                frames_file,
                args.frames,
                args.threshold,
                args.width,
                args.height,
                not args.no_check,
            )
            for score, nms in configs
        ]
        for fut in futures:
            sim = fut.result()
            sims.append(sim)
            print(
                f"bench: {sim['config']}: input {sim['input_clocks_per_pixel']:.5f} clocks/pixel, "
                f"frame intervals {sim['frame_interval_clocks']} clocks, "
                f"latency {sim['latency_clocks']} clocks, "
                f"{sim['sim_pixels_per_second']:.0f} pixels/s simulated"
            )

    memory = [
        {"config": f"{s}-{n}-{args.width}", **region_memory(args.width, args.height, SCORE_BITS[s])}
        for s, n in configs
        if n.startswith("region")
    ]
    summary = {
        "frames": {
            "count": args.frames,
            "width": args.width,
            "height": args.height,
            "threshold": args.threshold,
            "photographs": sources,
            "fit": "cv2.resize to cover, centre crop",
        },
        "simulation": sims,
        "region_memory": memory,
        "software": software,
        "machine": {
            **machine(),
            "ghdl": ghdl_version(),
            "parallel_simulations": args.jobs,
            "load_before": load,
        },
        "source": source,
        "wall_seconds": time.perf_counter() - start,
    }
    args.out.write_text(json.dumps(summary, indent=1) + "\n")
    print(
        f"bench: wrote {args.out.relative_to(REPO) if args.out.is_relative_to(REPO) else args.out}"
    )
    if not args.no_report:
        path = report.update_bench(summary)
        print(f"bench: rewrote the bench section of {path.relative_to(REPO)}")


if __name__ == "__main__":
    main()
