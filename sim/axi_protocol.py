"""AXI protocol checker for the ports of fastnms_axi, attached to every cocotb test of the
top (fastnms.sim.driver.AxiTop starts it; sim/frame_tb.py too).

Checked at every rising edge of aclk, on the values settled after the edge:
- during reset: every VALID the top drives (m_axis_corners, m_axis_score, B, R) is 0 from
  the first edge at which aresetn is sampled low (AXI: "VALID low during reset"); the
  testbench's own masters may drop their VALIDs as they assert aresetn;
- out of reset, on every channel (inputs and outputs): VALID is 0 or 1, never X/U/Z; while
  VALID is 1 the payload has no X/U/Z bit; once VALID is 1 without READY, VALID stays 1
  and the payload stays unchanged until the handshake;
- the corner records: TKEEP all ones, TLAST equal to the record's LAST bit on its final
  beat and 0 on the others, the flags EMPTY/ABORTED/OVERFLOW/ERROR only on a LAST record,
  EMPTY with x = y = score = area = 0 and never with ORB, no AREA with ORB (the region
  NMS has no ORB), the reserved bits 0; a record with ORB is REC_ORB_BEATS beats (record
  format 2), bits 63:32 of its angle beat 0;
- AXI4-Lite: no B response without a write address and data taken before it, no R response
  without a read address taken before it.

A violation raises AssertionError in the checker's task, which fails the running test.
"""

from __future__ import annotations

from dataclasses import dataclass, field

import cocotb
from cocotb.triggers import FallingEdge, ReadOnly, RisingEdge

from . import regs
from .records import RESERVED

ANGLE_RESERVED = ~regs.REC_ANGLE.mask & (1 << 64) - 1


@dataclass
class Channel:
    name: str
    valid: object
    ready: object | None
    payload: list = field(default_factory=list)
    driven_by_top: bool = False
    held: tuple | None = None  # payload of a VALID without READY on the last edge


def _value(sig) -> str:
    return str(sig.value)


class AxiProtocolChecker:
    """Create with the DUT (fastnms_axi) and call start()."""

    def __init__(self, dut, score_video: bool):
        self.dut = dut
        d = dut
        self.channels = [
            Channel(
                "s_axis_video",
                d.s_axis_video_tvalid,
                d.s_axis_video_tready,
                [d.s_axis_video_tdata, d.s_axis_video_tuser, d.s_axis_video_tlast],
            ),
            Channel(
                "m_axis_corners",
                d.m_axis_corners_tvalid,
                d.m_axis_corners_tready,
                [d.m_axis_corners_tdata, d.m_axis_corners_tkeep, d.m_axis_corners_tlast],
                driven_by_top=True,
            ),
            Channel(
                "s_axi_ctrl AW",
                d.s_axi_ctrl_awvalid,
                d.s_axi_ctrl_awready,
                [d.s_axi_ctrl_awaddr, d.s_axi_ctrl_awprot],
            ),
            Channel(
                "s_axi_ctrl W",
                d.s_axi_ctrl_wvalid,
                d.s_axi_ctrl_wready,
                [d.s_axi_ctrl_wdata, d.s_axi_ctrl_wstrb],
            ),
            Channel(
                "s_axi_ctrl B",
                d.s_axi_ctrl_bvalid,
                d.s_axi_ctrl_bready,
                [d.s_axi_ctrl_bresp],
                driven_by_top=True,
            ),
            Channel(
                "s_axi_ctrl AR",
                d.s_axi_ctrl_arvalid,
                d.s_axi_ctrl_arready,
                [d.s_axi_ctrl_araddr, d.s_axi_ctrl_arprot],
            ),
            Channel(
                "s_axi_ctrl R",
                d.s_axi_ctrl_rvalid,
                d.s_axi_ctrl_rready,
                [d.s_axi_ctrl_rdata, d.s_axi_ctrl_rresp],
                driven_by_top=True,
            ),
        ]
        # The score video's VALID must be low without SCORE_VIDEO too: checked as well.
        self.channels.append(
            Channel(
                "m_axis_score",
                d.m_axis_score_tvalid,
                d.m_axis_score_tready,
                [d.m_axis_score_tdata, d.m_axis_score_tuser, d.m_axis_score_tlast]
                if score_video
                else [],
                driven_by_top=True,
            )
        )
        self.edges = 0
        self.checked_edges = 0  # edges out of reset, to show the checker ran
        self.reset_edges = 0  # edges with aresetn sampled low
        self.writes_pending = [0, 0]  # AW and W handshakes not answered yet
        self.reads_pending = 0
        self.payload_left = 0  # beats of the ORB record in progress still to come
        self.payload_last = False  # that record is its frame's last

    def start(self) -> None:
        cocotb.start_soon(self._run())

    def _fail(self, text: str) -> None:
        raise AssertionError(f"AXI protocol, clock {self.edges}: {text}")

    async def _run(self) -> None:
        dut = self.dut
        in_reset = True  # until the first edge that samples aresetn high
        await FallingEdge(dut.aclk)  # the clock's first rise (from U) is not an edge
        while True:
            await RisingEdge(dut.aclk)
            self.edges += 1
            sampled_low = _value(dut.aresetn) != "1"  # the value the DUT sampled
            await ReadOnly()
            if sampled_low:
                in_reset = True
                self.reset_edges += 1
                for ch in self.channels:
                    ch.held = None
                    if ch.driven_by_top and _value(ch.valid) != "0":
                        self._fail(f"{ch.name} VALID is {_value(ch.valid)} during reset")
                self.writes_pending = [0, 0]
                self.reads_pending = 0
                self.payload_left = 0
                continue
            if in_reset:
                in_reset = False
                for ch in self.channels:
                    ch.held = None
            self.checked_edges += 1
            # A master may drop its VALIDs as it asserts aresetn (before the DUT sees it).
            entering_reset = _value(dut.aresetn) != "1"
            for ch in self.channels:
                if entering_reset and not ch.driven_by_top:
                    ch.held = None
                else:
                    self._check_channel(ch)

    def _check_channel(self, ch: Channel) -> None:
        valid = _value(ch.valid)
        if valid not in ("0", "1"):
            self._fail(f"{ch.name} VALID is {valid}")
        payload = tuple(_value(s) for s in ch.payload)
        if ch.held is not None:
            if valid != "1":
                self._fail(f"{ch.name} VALID fell before READY")
            if payload != ch.held:
                self._fail(f"{ch.name} payload changed before READY: {ch.held} -> {payload}")
        if valid != "1":
            return
        for sig, bits in zip(ch.payload, payload, strict=True):
            if any(b not in "01" for b in bits):
                self._fail(f"{ch.name} {sig._name} = {bits} while VALID")
        ready = ch.ready is None or _value(ch.ready) == "1"
        ch.held = None if ready else payload
        if ch.name == "m_axis_corners":
            self._check_record(payload, ready)
        if ready:
            self._count(ch.name)

    def _count(self, name: str) -> None:
        if name == "s_axi_ctrl AW":
            self.writes_pending[0] += 1
        elif name == "s_axi_ctrl W":
            self.writes_pending[1] += 1
        elif name == "s_axi_ctrl B":
            if min(self.writes_pending) < 1:
                self._fail("a write response without a write address and data before it")
            self.writes_pending = [n - 1 for n in self.writes_pending]
        elif name == "s_axi_ctrl AR":
            self.reads_pending += 1
        elif name == "s_axi_ctrl R":
            if self.reads_pending < 1:
                self._fail("a read response without a read address before it")
            self.reads_pending -= 1

    def _check_record(self, payload: tuple[str, ...], taken: bool) -> None:
        data, keep, last = payload
        word = int(data, 2)
        if keep != "1" * len(keep):
            self._fail(f"m_axis_corners TKEEP = {keep}")
        if self.payload_left:
            beat = regs.REC_ORB_BEATS - self.payload_left
            final = self.payload_left == 1
            if int(last) != int(final and self.payload_last):
                self._fail(f"TLAST {last} on beat {beat} of an ORB record")
            if beat == regs.REC_ANGLE_BEAT and word & ANGLE_RESERVED:
                self._fail(f"angle beat 0x{word:016x}: bits 63:32 set")
            if taken:
                self.payload_left -= 1
            return
        flag_last = regs.REC_LAST.get(word)
        orb = regs.REC_ORB.get(word)
        if int(last) != (flag_last and not orb):
            self._fail(f"TLAST {last} on a record with LAST {flag_last}, ORB {orb}")
        if orb and regs.REC_EMPTY.get(word):
            self._fail(f"record 0x{word:016x}: EMPTY with ORB")
        if orb and taken:
            self.payload_left, self.payload_last = regs.REC_ORB_BEATS - 1, bool(flag_last)
        flags = (
            regs.REC_EMPTY.mask
            | regs.REC_ABORTED.mask
            | regs.REC_OVERFLOW.mask
            | regs.REC_ERROR.mask
        )
        if word & flags and not flag_last:
            self._fail(f"record 0x{word:016x}: EMPTY/ABORTED/OVERFLOW/ERROR without LAST")
        if orb and regs.REC_AREA.get(word):
            self._fail(f"record 0x{word:016x}: AREA with ORB")
        corner = regs.REC_X.mask | regs.REC_Y.mask | regs.REC_SCORE.mask | regs.REC_AREA.mask
        if regs.REC_EMPTY.get(word) and word & corner:
            self._fail(f"record 0x{word:016x}: EMPTY with a corner")
        if word & RESERVED:
            self._fail(f"record 0x{word:016x}: reserved bits set")
