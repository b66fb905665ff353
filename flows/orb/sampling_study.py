"""How many clocks the sampling of one keypoint takes in the designs weighed for
fastnms_orb_sample (docs/orb_rtl.md, *The comparisons*), over tenth-degree angles:
`python -m flows.orb.sampling_study`.

Each design reads the 512 rotated points LANES per clock in the pattern's order; a
memory with P read ports serves at most P points of a step per clock, so a step takes
ceil(most points on one memory / P) clocks and a keypoint the sum over its steps:
- rows: the row buffers read directly, one block RAM per image row, two ports each;
- skewed: a copy of the patch in 37 memories, pixel (row, column) in memory
  (row + column) mod 37 (a column then writes each memory once), two ports each;
- copies (the design built): every lane its own copy, one clock per step.
"""

from __future__ import annotations

import numpy as np
from fastnms.golden import orb


def clocks(memory: np.ndarray, lanes: int, ports: int) -> np.ndarray:
    """Clocks per keypoint: memory (angles, 512) is the memory each point reads."""
    steps = memory.reshape(len(memory), -1, lanes)
    out = np.zeros(len(memory), dtype=np.int64)
    for k, keypoint in enumerate(steps):
        for step in keypoint:
            out[k] += -(-np.bincount(step).max() // ports)
    return out


def main() -> None:
    deg = np.arange(0, 3600, dtype=np.float32) / np.float32(10)
    a, b = orb.cos_sin(deg)
    dx, dy = orb.sample_offsets(a, b)
    row, column = dy + 18, dx + 18
    for lanes in (8, 16):
        print(f"LANES {lanes}: ideal {512 // lanes} clocks per keypoint")
        for name, memory in (("rows", row), ("skewed", (row + column) % 37)):
            c = clocks(memory, lanes, ports=2)
            print(f"  {name:7s} max {c.max():3d}  mean {c.mean():5.1f}")


if __name__ == "__main__":
    main()
