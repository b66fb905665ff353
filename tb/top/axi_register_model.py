"""RegisterModel: what the registers of an idle fastnms_axi (no video) read after any
AXI4-Lite writes, for the random register test (axi_registers_tb.registers_random).
"""

from __future__ import annotations

from fastnms.sim import regs

from tb.top.axi_common import (
    MAX_HEIGHT,
    MAX_WIDTH,
    all_generics,
    budget_register,
)


class RegisterModel:
    """What the registers of an idle top (no video) read after any writes: the
    read/write fields with byte strobes, WIDTH/HEIGHT clamped after the byte merge,
    MODE and the read-only registers fixed, STATUS and CMD reading 0."""

    def __init__(self) -> None:
        generics = all_generics()
        self.values = {r.offset: regs.reset_value(n, generics) for n, r in regs.REGISTERS.items()}
        self.rw_mask = {
            r.offset: sum(f.mask for f in r.fields.values() if f.access == "rw")
            for r in regs.REGISTERS.values()
        }

    def write(self, offset: int, data: int, strobe: int) -> None:
        if offset not in self.values:
            return
        bytes_mask = sum(0xFF << 8 * b for b in range(4) if strobe >> b & 1)
        if offset in (regs.WIDTH, regs.HEIGHT):
            limit = MAX_WIDTH if offset == regs.WIDTH else MAX_HEIGHT
            merged = (self.values[offset] & ~bytes_mask) | (data & bytes_mask)
            if merged >> 16 == 0 and (merged & 0xFFFF) < 7:
                merged = 7
            elif merged >> 16 or merged > limit:
                merged = limit
            self.values[offset] = merged
        elif offset == regs.BUDGET:
            merged = (self.values[offset] & ~bytes_mask) | (data & bytes_mask)
            self.values[offset] = budget_register(merged)
        elif offset != regs.MODE:
            keep = self.rw_mask[offset] & bytes_mask
            self.values[offset] = (self.values[offset] & ~keep) | (data & keep)

    def read(self, offset: int) -> int | None:
        """The value, or None for an address outside the map (SLVERR)."""
        return self.values.get(offset)
