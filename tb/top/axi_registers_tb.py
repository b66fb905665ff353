"""cocotb tests of fastnms_axi's registers: reset values, clamping, read-only and
unmapped addresses, byte strobes, write-1-to-clear (registers); random writes and
concurrent reads against axi_register_model.RegisterModel (registers_random).
Shared driver and configuration: tb/top/axi_common.py.
"""

from __future__ import annotations

import cocotb
from cocotb.triggers import ClockCycles
from cocotbext.axi import AxiResp
from fastnms.sim import regs
from fastnms.sim.driver import pauses
from fastnms.testing import images as testimages

from tb.top.axi_common import (
    MAX_HEIGHT,
    MAX_PER_CELL,
    MAX_WIDTH,
    PPC,
    TB,
    TIMEOUT_MS,
    all_generics,
    budget_register,
    golden,
    width_register,
)
from tb.top.axi_register_model import RegisterModel


@cocotb.test(timeout_time=TIMEOUT_MS, timeout_unit="ms")
async def registers(dut):
    """ID, VERSION, reset values, read/write, clamping, MODE, read-only and
    unmapped addresses, partial writes, write-1-to-clear."""
    tb = await TB.create(dut, 0, 0)
    await tb.reset()
    generics = all_generics()
    for name, reg in regs.REGISTERS.items():
        value = await tb.read(reg.offset)
        assert value == regs.reset_value(name, generics), f"{name} = 0x{value:08x} after reset"
    assert await tb.read(regs.ID) == 0x46415354
    major, minor, patch = regs.MAP_VERSION
    assert await tb.read(regs.VERSION) == major << 16 | minor << 8 | patch

    await tb.write(regs.THRESHOLD, 0xFFFFFF37)
    assert await tb.read(regs.THRESHOLD) == 0x37
    for written in [0, 6, 7, 8, 9, 10, 11, MAX_WIDTH, MAX_WIDTH - 1, MAX_WIDTH + 1]:
        await tb.write(regs.WIDTH, written)
        want = width_register(written)
        assert await tb.read(regs.WIDTH) == want, f"WIDTH write {written}: want {want}"
    for written in [0x10000 | 9, 0xFFFFFFFF]:
        await tb.write(regs.WIDTH, written)
        assert await tb.read(regs.WIDTH) == MAX_WIDTH, f"WIDTH write 0x{written:x}"
    assert regs.MODE_PPC.get(await tb.read(regs.MODE)) == PPC
    await tb.write(regs.HEIGHT, MAX_HEIGHT + 5)
    assert await tb.read(regs.HEIGHT) == MAX_HEIGHT
    await tb.write(regs.HEIGHT, 3)
    assert await tb.read(regs.HEIGHT) == 7
    assert regs.BUILD_MAX_PER_CELL.get(await tb.read(regs.BUILD)) == MAX_PER_CELL
    for k in range(16):
        for cell in (0, 15, 16, 17, 31, 32, 48, 64, 100, 128, 255, 256, 257, 511, 0x7F00):
            written = k | cell << 16
            await tb.write(regs.BUDGET, written)
            want = budget_register(written)
            got = await tb.read(regs.BUDGET)
            assert got == want, f"BUDGET write 0x{written:x}: 0x{got:x}, want 0x{want:x}"
    await tb.write(regs.BUDGET, 0)

    # MODE: asking for a variant that is not built in changes nothing.
    mode = await tb.read(regs.MODE)
    for ask in (0x00, 0x11, 0x33, 0x21, 0xFFFFFFFF):
        await tb.write(regs.MODE, ask)
        assert await tb.read(regs.MODE) == mode

    # Read-only registers ignore writes.
    read_only = [
        n for n, r in regs.REGISTERS.items() if all(f.access == "ro" for f in r.fields.values())
    ]
    assert {"ID", "DROPPED", "INPUT_STALLS"} <= set(read_only)
    for name in read_only:
        before = await tb.read(regs.REGISTERS[name].offset)
        await tb.write(regs.REGISTERS[name].offset, 0x5A5A5A5A)
        assert await tb.read(regs.REGISTERS[name].offset) == before, name

    # Full decoding: the registers answer at their offset only; any other address
    # of the 4 KiB space answers SLVERR (reads 0) and changes nothing.
    top = max(r.offset for r in regs.REGISTERS.values())
    for address in (top + 4, 0x100 + regs.THRESHOLD, 0x800 + regs.CTRL, 0xFFC):
        resp = await tb.axil.read(address, 4)
        assert resp.resp == AxiResp.SLVERR and resp.data == bytes(4), hex(address)
        resp = await tb.axil.write(address, (0).to_bytes(4, "little"))
        assert resp.resp == AxiResp.SLVERR, hex(address)
    assert await tb.read(regs.THRESHOLD) == 0x37
    assert await tb.read(regs.CTRL) == regs.CTRL_ENABLE.mask

    # Byte strobes: a byte not strobed keeps its value.
    resp = await tb.axil.write(regs.THRESHOLD, b"\x05")  # WSTRB 0001
    assert resp.resp == AxiResp.OKAY
    assert await tb.read(regs.THRESHOLD) == 0x05
    await tb.axil.write(regs.THRESHOLD + 1, b"\x77")  # WSTRB 0010: no THRESHOLD bit
    assert await tb.read(regs.THRESHOLD) == 0x05
    await tb.write(regs.WIDTH, 40)
    await tb.axil.write(regs.WIDTH + 1, b"\x00")  # WSTRB 0010: the high byte of 40
    assert await tb.read(regs.WIDTH) == 40
    await tb.axil.write(regs.WIDTH, b"\x21")  # WSTRB 0001
    assert await tb.read(regs.WIDTH) == width_register(0x21)
    await tb.axil.write(regs.WIDTH + 2, b"\x01")  # bits 31:16 set: clamped
    assert await tb.read(regs.WIDTH) == MAX_WIDTH
    await tb.axil.write(regs.CTRL + 1, b"\xff")  # no CTRL bit in byte 1
    assert await tb.read(regs.CTRL) == regs.CTRL_ENABLE.mask

    # CTRL read/write.
    await tb.write(regs.CTRL, 0b100)
    assert await tb.read(regs.CTRL) == 0b100
    await tb.write(regs.CTRL, regs.CTRL_LIVE.mask | regs.CTRL_ENABLE.mask)
    assert await tb.read(regs.CTRL) == regs.CTRL_LIVE.mask | regs.CTRL_ENABLE.mask
    await tb.write(regs.CTRL, 0b001)
    assert await tb.read(regs.CTRL) == 0b001

    # Write-1-to-clear: a frame sets FRAME_DONE; writing 0 keeps it, 1 clears it.
    await tb.configure(16, 9, 10)
    img = testimages.blurred_noise(tb.np_rng, 16, 9)
    await tb.send_frames([(img, 10)])
    await tb.receive(1, 5000)
    await ClockCycles(dut.aclk, 5)
    assert regs.STATUS_FRAME_DONE.get(await tb.status())
    await tb.write(regs.STATUS, 0)
    assert regs.STATUS_FRAME_DONE.get(await tb.status())
    await tb.axil.write(regs.STATUS + 1, b"\xff")  # WSTRB 0010: FRAME_DONE not strobed
    assert regs.STATUS_FRAME_DONE.get(await tb.status())
    await tb.write(regs.STATUS, regs.STATUS_FRAME_DONE.mask)
    assert await tb.status() == 0
    assert await tb.read(regs.FRAME_COUNT) == 1
    assert await tb.read(regs.CORNER_COUNT) == len(golden(img, 10))


@cocotb.test(timeout_time=TIMEOUT_MS, timeout_unit="ms")
async def registers_random(dut):
    """Random AXI4-Lite traffic against RegisterModel: writes of random data with
    random byte strobes to any address of the 4 KiB segment (mostly mapped ones),
    reads of any register between them, and all along, on the read channel, reads
    of the registers that writes cannot change; B and R back-pressure. CMD writes
    never carry the key (no soft reset)."""
    tb = await TB.create(dut, 0, 0)
    tb.axil.write_if.b_channel.set_pause_generator(pauses(tb.rng, 0.3))
    tb.axil.read_if.r_channel.set_pause_generator(pauses(tb.rng, 0.3))
    await tb.reset()
    model = RegisterModel()
    rng = tb.rng
    mapped = sorted(model.values)

    def address() -> int:
        if rng.random() < 0.85:
            return rng.choice(mapped)
        return rng.randrange(0, 0x1000, 4)

    async def check_read(offset: int) -> None:
        """A read equal to the model: the value with OKAY, or SLVERR and 0 outside the map."""
        resp = await tb.axil.read(offset, 4)
        want = model.read(offset)
        got = int.from_bytes(resp.data, "little")
        assert (resp.resp == AxiResp.SLVERR) == (want is None), hex(offset)
        assert got == (want or 0), f"read 0x{offset:03x}: 0x{got:08x}, model {want}"

    async def reader(count: int) -> None:
        for _ in range(count):
            await check_read(address())

    fixed = [o for o in mapped if not model.rw_mask[o] and o not in (regs.STATUS, regs.CMD)]
    done = False

    async def fixed_reader() -> int:
        count = 0
        while not done:
            await check_read(rng.choice(fixed + [0x100, 0xFFC]))
            count += 1
        return count

    background = cocotb.start_soon(fixed_reader())
    writes = 300
    for _ in range(writes):
        offset = address()
        first = rng.randrange(4)
        length = rng.randrange(1, 5 - first)
        data = rng.getrandbits(32)
        if offset == regs.CMD:
            data &= ~(0xFF << regs.CMD_KEY.lsb)
        if rng.random() < 0.3:  # small values: the clamping's lower end
            data &= 0x0000000F
        payload = data.to_bytes(4, "little")[first : first + length]
        resp = await tb.axil.write(offset + first, payload)
        strobe = ((1 << length) - 1) << first
        if model.read(offset) is None:
            assert resp.resp == AxiResp.SLVERR, hex(offset)
        else:
            assert resp.resp == AxiResp.OKAY, hex(offset)
        model.write(offset, data, strobe)
        if rng.random() < 0.3:
            await reader(rng.randrange(1, 4))
    done = True
    concurrent = await background
    assert concurrent > 20, f"only {concurrent} reads beside the writes"
    await reader(100)
    for offset in mapped:
        await check_read(offset)
    dut._log.info(
        "%d random writes, %d concurrent reads, every read equal to the model", writes, concurrent
    )
