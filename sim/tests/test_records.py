"""The Python record decoder (fastnms.sim.records) and sim/run.py's decode_frame on
hand-built words, without an engine: the region NMS's AREA (bits 63:53) with each corner,
2047 the largest, 0 in the EMPTY record. (sw/tests/test_sw_records.py holds the C and
Python decoders to the same output on more streams.)"""

from __future__ import annotations

import numpy as np
import pytest
from fastnms.golden.nms import AREA_BITS, AREA_MAX
from fastnms.sim import regs
from fastnms.sim.records import RecordDecoder, decode_records
from fastnms.sim.run import SimError, decode_frame


def word(x=0, y=0, score=0, area=0, *, last=False, empty=False) -> int:
    value = regs.REC_X.mask & x << regs.REC_X.lsb
    value |= regs.REC_Y.mask & y << regs.REC_Y.lsb
    value |= regs.REC_SCORE.mask & score << regs.REC_SCORE.lsb
    value |= regs.REC_AREA.mask & area << regs.REC_AREA.lsb
    value |= int(last) << regs.REC_LAST.lsb | int(empty) << regs.REC_EMPTY.lsb
    return value


EMPTY = word(last=True, empty=True)


def test_area_field_is_the_golden_models():
    """The record's AREA field as the register map generates it: bits 63:53, as wide
    as the golden model's saturating area."""
    assert (regs.REC_AREA.lsb, regs.REC_AREA.width) == (53, AREA_BITS)
    assert regs.REC_AREA.mask >> regs.REC_AREA.lsb == AREA_MAX == 2047
    assert regs.MIN_AREA == 0x40 and regs.MIN_AREA_VALUE.width == AREA_BITS
    assert regs.REGISTERS["MIN_AREA"].fields == {"VALUE": regs.MIN_AREA_VALUE}


def test_areas_decode_with_their_corners():
    words = [
        word(5, 3, 40, 1),
        word(9, 4, 30, AREA_MAX),
        word(0xFFFF, 0xFFFF, 0xFFF, AREA_MAX),  # every bit of x, y, score and area
        word(7, 9, 50, 0, last=True),  # AREA 0: the other NMS
        EMPTY,
        word(3, 3, 20, 12, last=True),
    ]
    assert words[2] >> regs.REC_AREA.lsb == AREA_MAX
    frames = decode_records(words)
    assert len(frames) == 3
    first, empty, last = frames
    assert first.corners == [(5, 3, 40), (9, 4, 30), (0xFFFF, 0xFFFF, 0xFFF), (7, 9, 50)]
    assert first.areas == [1, AREA_MAX, AREA_MAX, 0]
    assert not first.malformed and first.flags == []
    assert empty.flags == ["empty"] and empty.corners == [] and empty.areas == []
    assert last.corners == [(3, 3, 20)] and last.areas == [12]
    # Word by word: the same frames.
    decoder = RecordDecoder()
    pieces = [f for w in words for f in decoder.feed([w])]
    assert decoder.flush() is None and pieces == frames


@pytest.mark.parametrize("area", [1, 2, AREA_MAX])
def test_empty_record_with_an_area_is_malformed(area: int):
    """AREA is 0 in the EMPTY record; another value is a field not 0."""
    bad, good = decode_records([word(area=area, last=True, empty=True), EMPTY])
    assert bad.empty and bad.malformed and bad.areas == []
    assert good.empty and not good.malformed


def test_decode_frame_sorts_areas_with_records():
    """run.py's decode_frame: the areas in the records' order (by y, then x), as
    FrameResult.areas holds them."""
    words = [word(8, 6, 11, 4), word(3, 4, 12, 9), word(5, 6, 13, AREA_MAX, last=True)]
    records, areas, angle_bits, descriptors = decode_frame(np.array(words, dtype=np.uint64))
    assert records.tolist() == [[3, 4, 12], [5, 6, 13], [8, 6, 11]]
    assert areas.dtype == np.int64 and areas.tolist() == [9, AREA_MAX, 4]
    assert angle_bits.shape == (0,) and descriptors.shape == (0, 32)
    records, areas, _, _ = decode_frame(np.array([EMPTY], dtype=np.uint64))
    assert records.shape == (0, 3) and areas.shape == (0,) and areas.dtype == np.int64
    with pytest.raises(SimError):
        decode_frame(np.array([word(area=3, last=True, empty=True)], dtype=np.uint64))
