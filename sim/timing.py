"""The timing a simulation drives around fastnms_axi: input idles, output
back-pressure and camera blanking. Both engines compute the same pause
patterns from a seed, so the same settings give the same clock counts.

A pause pattern is either a rate (each clock pauses with that probability,
drawn from a counter-based hash of the seed and the clock) or a string of
0/1 repeated clock after clock (1 = pause). Clock k of a pattern is the k-th
rising edge from the one where the video source gets its first frame;
sim/verilator_harness.cpp has the same function in C++.
"""

from __future__ import annotations

from collections.abc import Iterator
from dataclasses import dataclass

MASK64 = (1 << 64) - 1


def splitmix64(x: int) -> int:
    x = (x + 0x9E3779B97F4A7C15) & MASK64
    x = ((x ^ (x >> 30)) * 0xBF58476D1CE4E5B9) & MASK64
    x = ((x ^ (x >> 27)) * 0x94D049BB133111EB) & MASK64
    return x ^ (x >> 31)


@dataclass(frozen=True)
class Pattern:
    """When a driver pauses: never (the default), at a rate, or by a repeated bit string."""

    rate: float = 0.0
    bits: str = ""

    @classmethod
    def parse(cls, text: str) -> Pattern:
        """'0.25' (a rate in [0, 1)) or '0011' (bits, 1 = pause, repeated; at least two
        characters). Raises ValueError with a message for the user."""
        text = text.strip()
        if len(text) >= 2 and set(text) <= {"0", "1"}:
            if "0" not in text:
                raise ValueError(f"pattern {text!r} pauses on every clock")
            return cls(bits=text)
        try:
            rate = float(text)
        except ValueError:
            raise ValueError(
                f"expected a rate in [0, 1) or a pattern of 0 and 1, got {text!r}"
            ) from None
        if not 0.0 <= rate < 1.0:
            raise ValueError(f"rate must be in [0, 1), got {text}")
        return cls(rate=rate)

    @property
    def active(self) -> bool:
        return bool(self.bits) or self.rate > 0

    def __str__(self) -> str:
        return self.bits or f"{self.rate:g}"

    def at(self, key: int, k: int) -> bool:
        """Whether the driver pauses at clock k of the pattern."""
        if self.bits:
            return self.bits[k % len(self.bits)] == "1"
        if self.rate <= 0:
            return False
        return (splitmix64(key ^ splitmix64(k)) >> 11) * 2.0**-53 < self.rate

    def clocks(self, key: int) -> Iterator[bool]:
        k = 0
        while True:
            yield self.at(key, k)
            k += 1

    def job_line(self, name: str) -> str:
        if self.bits:
            return f"{name} bits {self.bits}\n"
        return f"{name} rate {self.rate!r}\n"


@dataclass(frozen=True)
class Timing:
    """Input idles (the video source withholds tvalid), output stalls (the corner
    sink holds tready low), both seeded; blanking clocks after each line (hblank)
    and after each frame's last line instead (vblank), fast engine only."""

    idle: Pattern = Pattern()
    stall: Pattern = Pattern()
    seed: int = 1
    hblank: int = 0
    vblank: int = 0

    @property
    def idle_key(self) -> int:
        return splitmix64((self.seed * 2) & MASK64)

    @property
    def stall_key(self) -> int:
        return splitmix64((self.seed * 2 + 1) & MASK64)

    def as_dict(self) -> dict[str, object]:
        return {
            "idle": str(self.idle),
            "stall": str(self.stall),
            "seed": self.seed,
            "hblank": self.hblank,
            "vblank": self.vblank,
        }
