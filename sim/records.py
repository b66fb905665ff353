"""The corner records of m_axis_corners (64-bit words) decoded into frames of corners:
the Python twin of the C decoder in sw/fastnms.c, with the same rules.

A frame is the records up to and including one with LAST. Every record that is not
EMPTY is a corner (x, y, score), an ABORTED one included (the record the soft reset
closed the frame with), with its AREA in `areas` (the region's corner pixels with the
region NMS, saturating at 2047; 0 with the other NMS). EMPTY is the only record of a
frame without corners, with LAST and x = y = score = area = 0; with CTRL.LIVE = 1,
records of earlier frames whose LAST record was dropped may precede it, and the LAST
record then carries OVERFLOW. A record that breaks these rules marks its frame
`malformed` (decoding goes on; the next LAST ends the frame).

Record format 2 (a build with DESCRIPTOR = "orb"): a record whose first word has ORB
set is REC_ORB_BEATS words, the angle (float32 bits, beat 1) and the 32 descriptor
bytes (beats 2 .. 5) after it; the frame's LAST record ends with its last word. A
frame whose first record has ORB (`orb`) has `angle_bits` and `descriptors`, one entry
per corner (0 and zero bytes for a corner without a complete payload). ORB with EMPTY,
or a frame mixing records with and without ORB, is malformed.

    frames = decode_records(words)          # all at once
    decoder = RecordDecoder()               # or buffer by buffer
    for buffer in buffers:
        for frame in decoder.feed(buffer): ...
    tail = decoder.flush()                  # a frame without LAST, or None
"""

from __future__ import annotations

from collections.abc import Iterable
from dataclasses import dataclass, field

from . import regs

Corner = tuple[int, int, int]

# The fields that are 0 in the EMPTY record.
_FIELDS = regs.REC_X.mask | regs.REC_Y.mask | regs.REC_SCORE.mask | regs.REC_AREA.mask
# The bits of beat 0 that no field uses (0 in every record).
RESERVED = ((1 << 64) - 1) & ~(
    _FIELDS
    | regs.REC_ERROR.mask
    | regs.REC_EMPTY.mask
    | regs.REC_LAST.mask
    | regs.REC_ABORTED.mask
    | regs.REC_OVERFLOW.mask
    | regs.REC_ORB.mask
)


@dataclass
class Frame:
    index: int  # frames delivered by the decoder before this one
    first_word: int  # position of the frame's first record in the whole stream
    corners: list[Corner] = field(default_factory=list)  # (x, y, score), in output order
    areas: list[int] = field(default_factory=list)  # AREA per corner (0 without region NMS)
    records: int = 0  # records of the frame, the EMPTY record included
    words: int = 0  # 64-bit words of the frame (= records unless ORB)
    angle_bits: list[int] = field(default_factory=list)  # ORB: float32 bits per corner
    descriptors: list[bytes] = field(default_factory=list)  # ORB: 32 bytes per corner
    empty: bool = False  # ended by the EMPTY record
    aborted: bool = False  # a soft reset cut the frame
    overflow: bool = False  # records of this frame, or whole frames before it, were dropped
    error: bool = False  # an internal error reset the pipeline: records or frames were lost
    malformed: bool = False  # a record broke the format
    complete: bool = True  # False: the stream ended before the frame's LAST record
    orb: bool = False  # its first record has ORB (record format 2)

    @property
    def flags(self) -> list[str]:
        """The names of the flags that are set, in the order of the C decoder's bits."""
        names = ("empty", "aborted", "overflow", "incomplete", "malformed", "orb", "error")
        values = (
            self.empty,
            self.aborted,
            self.overflow,
            not self.complete,
            self.malformed,
            self.orb,
            self.error,
        )
        return [n for n, v in zip(names, values, strict=True) if v]


class RecordDecoder:
    """Decodes a record stream fed in pieces; a frame may span several pieces."""

    def __init__(self) -> None:
        self.position = 0  # words fed so far
        self.frames = 0  # frames delivered so far
        self._frame: Frame | None = None  # the frame in progress
        self._payload: list[int] = []  # the ORB words of the record in progress
        self._payload_left = 0  # ORB words still to come for it
        self._payload_last = False  # that record is its frame's last
        self._payload_keep = False  # that record is a corner (not EMPTY)

    @property
    def pending(self) -> int:
        """Records of the frame in progress (0 between frames)."""
        return self._frame.records if self._frame else 0

    def feed(self, words: Iterable[int]) -> list[Frame]:
        """The frames that end in `words` (each word an unsigned 64-bit integer)."""
        done = []
        for word in words:
            word = int(word)
            if not 0 <= word < 1 << 64:
                raise ValueError(f"record word {word:#x} is not a 64-bit unsigned value")
            if self._take(word):
                done.append(self._deliver(complete=True))
        return done

    def flush(self) -> Frame | None:
        """The frame in progress (complete=False), if any; the next word starts a new frame."""
        return self._deliver(complete=False) if self._frame else None

    def _take(self, word: int) -> bool:
        if self._frame is None:
            self._frame = Frame(index=self.frames, first_word=self.position)
        frame = self._frame
        self.position += 1
        frame.words += 1
        if self._payload_left:
            return self._take_payload(frame, word)
        frame.records += 1
        orb = bool(regs.REC_ORB.get(word))
        if frame.records == 1:
            frame.orb = orb
        elif orb != frame.orb:
            frame.malformed = True  # records with and without ORB
        empty, last = bool(regs.REC_EMPTY.get(word)), bool(regs.REC_LAST.get(word))
        aborted, overflow = bool(regs.REC_ABORTED.get(word)), bool(regs.REC_OVERFLOW.get(word))
        error = bool(regs.REC_ERROR.get(word))
        if empty:
            frame.empty = True
            lost = overflow or error
            if (
                not last
                or aborted
                or word & (_FIELDS | RESERVED)
                or (frame.records != 1 and not lost)
            ):
                frame.malformed = True
        else:
            frame.corners.append(
                (regs.REC_X.get(word), regs.REC_Y.get(word), regs.REC_SCORE.get(word))
            )
            frame.areas.append(regs.REC_AREA.get(word))
            if frame.orb:  # until its payload is complete
                frame.angle_bits.append(0)
                frame.descriptors.append(bytes(32))
        frame.aborted |= aborted
        frame.overflow |= overflow
        frame.error |= error
        if (aborted or overflow or error) and not last:
            frame.malformed = True
        if orb:
            if empty:
                frame.malformed = True
            self._payload, self._payload_left = [], regs.REC_ORB_BEATS - 1
            self._payload_last, self._payload_keep = last, not empty
            return False
        return last

    def _take_payload(self, frame: Frame, word: int) -> bool:
        self._payload.append(word)
        self._payload_left -= 1
        if self._payload_left:
            return False
        angle = regs.REC_ANGLE.get(self._payload[regs.REC_ANGLE_BEAT - 1])
        first = regs.REC_DESCRIPTOR_BEAT - 1
        words = self._payload[first : first + regs.REC_DESCRIPTOR_BEATS]
        if self._payload_keep and frame.orb:
            frame.angle_bits[-1] = angle
            frame.descriptors[-1] = b"".join(w.to_bytes(8, "little") for w in words)
        return self._payload_last

    def _deliver(self, complete: bool) -> Frame:
        frame = self._frame
        assert frame is not None
        frame.complete = complete
        self._frame = None
        self._payload_left = 0
        self.frames += 1
        return frame


def decode_records(words: Iterable[int]) -> list[Frame]:
    """Every frame of a record stream; a last frame without LAST is included with
    complete=False."""
    decoder = RecordDecoder()
    frames = decoder.feed(words)
    tail = decoder.flush()
    return frames if tail is None else [*frames, tail]
