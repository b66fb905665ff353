"""The two record decoders, C (sw/fastnms.c, through sw/tests/decode_records.c) and
Python (fastnms.sim.records), on the records the RTL emits (fastnms_axi on the fast
engine) against each other and the golden model, and on hand-built streams: pieces,
EMPTY, ABORTED and OVERFLOW frames, the region NMS's AREA, a stream that stops mid-frame,
corner storage too small, malformed records, random words."""

from __future__ import annotations

import subprocess
import zlib
from pathlib import Path

import numpy as np
import pytest
from fastnms.golden.model import detect
from fastnms.sim import regs
from fastnms.sim.records import Frame, RecordDecoder, decode_records
from fastnms.sim.run import SimResult, run_rtl
from fastnms.testing import images as testimages
from fastnms.testing.fixtures import SEED

# The order of the C decoder's flag bits (FASTNMS_FRAME_*) in its output.
C_FLAGS = ["empty", "aborted", "overflow", "incomplete", "malformed", "truncated", "orb", "error"]


def rec(
    x=0,
    y=0,
    score=0,
    *,
    area=0,
    last=False,
    empty=False,
    aborted=False,
    overflow=False,
    orb=False,
) -> int:
    """One record word (with `orb`, the first word of a record in format 2)."""
    word = x << regs.REC_X.lsb | y << regs.REC_Y.lsb | score << regs.REC_SCORE.lsb
    word |= area << regs.REC_AREA.lsb
    for flag, fld in [
        (last, regs.REC_LAST),
        (empty, regs.REC_EMPTY),
        (aborted, regs.REC_ABORTED),
        (overflow, regs.REC_OVERFLOW),
        (orb, regs.REC_ORB),
    ]:
        word |= int(flag) << fld.lsb
    return word


EMPTY = rec(last=True, empty=True)


def render(frames: list[Frame], capacity: int | None = None, orb: bool = True) -> str:
    """Frames in the C test program's format, with room for `capacity` corners per frame
    (and their ORB payloads unless `orb` is False: the one-shot mode keeps none)."""
    lines = []
    for f in frames:
        stored = len(f.corners) if capacity is None else min(capacity, len(f.corners))
        flags = f.flags + (["truncated"] if stored < len(f.corners) else [])
        lines.append(
            f"frame {f.index} first {f.first_word} records {f.records} words {f.words}"
            f" corners {len(f.corners)} stored {stored}"
            f" flags {','.join(sorted(flags, key=C_FLAGS.index)) or '-'}"
        )
        for i, (x, y, s) in enumerate(f.corners[:stored]):
            payload = f" {f.angle_bits[i]:08x} {f.descriptors[i].hex()}" if f.orb and orb else ""
            area = f" area {f.areas[i]}" if f.areas[i] else ""
            lines.append(f"{x} {y} {s}{payload}{area}")
    return "".join(line + "\n" for line in lines)


def run_c(program: Path, tmp_path: Path, words, *args) -> str:
    path = tmp_path / "records.bin"
    np.asarray(words, dtype="<u8").tofile(path)
    if program.name == "decode_records" and args and args[0] == "--all":
        cmd = [program, "--all", path, *map(str, args[1:])]
    else:
        cmd = [program, path, *map(str, args)]
    result = subprocess.run(cmd, capture_output=True, text=True, timeout=30)
    assert result.returncode == 0, result.stdout + result.stderr
    return result.stdout


def c_stream(c_programs, tmp_path, words, chunk=0, capacity=None) -> str:
    """The C decoder fed `chunk` words at a time (0: all), `capacity` corners of room."""
    args = [chunk or len(words) or 1] + ([] if capacity is None else [capacity])
    return run_c(c_programs["decode_records"], tmp_path, words, *args)


def py_stream(words, chunk=0) -> list[Frame]:
    decoder = RecordDecoder()
    words = list(words)
    chunk = chunk or len(words) or 1
    frames = []
    for at in range(0, len(words), chunk):
        frames += decoder.feed(words[at : at + chunk])
    tail = decoder.flush()
    return frames if tail is None else [*frames, tail]


def decoded(c_programs, tmp_path, words, chunks=(0, 1, 2, 3)) -> list[Frame]:
    """The Python decoder's frames, after checking that the C decoder and the Python
    one fed in pieces give the same."""
    frames = decode_records(words)
    expected = render(frames)
    for chunk in chunks:
        assert render(py_stream(words, chunk)) == expected, f"python, chunk {chunk}"
        assert c_stream(c_programs, tmp_path, words, chunk) == expected, f"C, chunk {chunk}"
    return frames


# ---- records the RTL emitted ----------------------------------------------------------


@pytest.fixture(scope="module", params=[("opencv", "3x3"), ("sad", "region4")], ids="-".join)
def rtl_run(request) -> tuple[str, str, list, SimResult]:
    """Three 32x24 frames back to back through fastnms_axi (the fast engine): blurred
    noise, a flat frame (no corner: the EMPTY record), blurred noise again."""
    score, nms = request.param
    rng = np.random.default_rng(SEED ^ zlib.crc32(b"sw/tests records"))
    frames = [
        (testimages.blurred_noise(rng, 32, 24), 6),
        (np.full((24, 32), 97, dtype=np.uint8), 20),
        (testimages.blurred_noise(rng, 32, 24), 10),
    ]
    return score, nms, frames, run_rtl(frames, score, nms)


def test_rtl_records_decode_to_the_golden_corners(rtl_run, c_programs, tmp_path):
    score, nms, frames_in, result = rtl_run
    words = np.concatenate([f.words for f in result.frames])
    frames = decode_records(words)
    assert len(frames) == len(frames_in)
    for i, ((img, t), got, sim) in enumerate(zip(frames_in, frames, result.frames, strict=True)):
        want = [tuple(int(v) for v in r) for r in detect(img, t, score, nms, with_area=True)]
        records = [(*c, a) for c, a in zip(got.corners, got.areas, strict=True)]
        assert sorted(records, key=lambda c: (c[1], c[0])) == want, f"frame {i}"
        assert got.complete and not (got.aborted or got.overflow or got.malformed)
        assert got.empty == (not want) and got.records == len(sim.words) == max(1, len(want))
    assert frames[1].empty and frames[1].corners == []
    assert sum(len(f.corners) for f in frames) >= 10, "too few corners for a test"
    # The C decoder, with the stream in one piece and cut anywhere.
    expected = render(frames)
    for chunk in (0, 1, 5, 64):
        assert c_stream(c_programs, tmp_path, words, chunk) == expected, f"chunk {chunk}"
        assert render(py_stream(words, chunk)) == expected, f"chunk {chunk}"
    total = sum(len(f.corners) for f in frames)
    got = run_c(c_programs["decode_records"], tmp_path, words, "--all", 3, total)
    assert got == expected + f"result 0 frames 3 corners {total}\n"


# ---- hand-built streams -------------------------------------------------------------


def test_no_records(c_programs, tmp_path):
    assert decoded(c_programs, tmp_path, []) == []
    got = run_c(c_programs["decode_records"], tmp_path, [], "--all", 0, 0)
    assert got == "result 0 frames 0 corners 0\n"


def test_frame_spanning_two_buffers(c_programs, tmp_path):
    words = [rec(3, 3, 30), rec(9, 4, 40), rec(5, 7, 50), rec(8, 8, 60, last=True), EMPTY]
    decoder = RecordDecoder()
    assert decoder.feed(words[:2]) == [] and decoder.pending == 2
    first, second = decoder.feed(words[2:])
    assert decoder.pending == 0 and decoder.flush() is None
    assert first.corners == [(3, 3, 30), (9, 4, 40), (5, 7, 50), (8, 8, 60)]
    assert (first.index, first.first_word, first.records, first.flags) == (0, 0, 4, [])
    assert (second.index, second.first_word, second.corners, second.flags) == (1, 4, [], ["empty"])
    assert decoded(c_programs, tmp_path, words, chunks=(0, 1, 2, 3, 4)) == [first, second]


def test_empty_frames(c_programs, tmp_path):
    frames = decoded(c_programs, tmp_path, [EMPTY, EMPTY, rec(4, 5, 6, last=True), EMPTY])
    assert [f.flags for f in frames] == [["empty"], ["empty"], [], ["empty"]]
    assert [len(f.corners) for f in frames] == [0, 0, 1, 0]


def test_aborted_frame(c_programs, tmp_path):
    """A soft reset closes the frame with the record the packer held, marked ABORTED:
    a corner like the others."""
    words = [rec(3, 3, 21), rec(6, 3, 22, last=True, aborted=True), rec(4, 4, 23, last=True)]
    first, second = decoded(c_programs, tmp_path, words)
    assert first.aborted and first.corners == [(3, 3, 21), (6, 3, 22)] and not first.malformed
    assert not second.aborted and second.corners == [(4, 4, 23)]


def test_overflow_frames(c_programs, tmp_path):
    """Live mode: a frame whose LAST record was dropped runs into the next one, whose
    LAST record carries OVERFLOW; the next frame may be empty."""
    words = [
        rec(3, 3, 1),
        rec(5, 9, 2),  # this frame's LAST record was dropped
        rec(4, 3, 3, last=True, overflow=True),
        rec(3, 3, 4),  # and again, before an empty frame
        rec(last=True, empty=True, overflow=True),
        EMPTY,
    ]
    merged, into_empty, empty = decoded(c_programs, tmp_path, words)
    assert merged.overflow and merged.corners == [(3, 3, 1), (5, 9, 2), (4, 3, 3)]
    assert into_empty.flags == ["empty", "overflow"] and into_empty.corners == [(3, 3, 4)]
    assert empty.flags == ["empty"]


def test_stream_ending_mid_frame(c_programs, tmp_path):
    """The records after the last LAST are a frame too, reported incomplete, not lost;
    the decoder takes the next word as a new frame."""
    words = [rec(3, 3, 1, last=True), rec(7, 3, 2), rec(3, 8, 3)]
    done, tail = decoded(c_programs, tmp_path, words)
    assert done.complete and not tail.complete and tail.flags == ["incomplete"]
    assert (tail.index, tail.first_word, tail.records) == (1, 1, 2)
    assert tail.corners == [(7, 3, 2), (3, 8, 3)]
    decoder = RecordDecoder()
    assert len(decoder.feed(words)) == 1 and decoder.pending == 2
    assert decoder.flush() == tail and decoder.flush() is None
    (after,) = decoder.feed([EMPTY])
    assert (after.index, after.first_word, after.flags) == (2, 3, ["empty"])


def test_storage_too_small(c_programs, tmp_path):
    """Stream: each frame keeps the corners that fit and is TRUNCATED; one shot: an
    error with the sizes needed; never a write out of the arrays (the sanitizers watch)."""
    words = [rec(3, 3 + i, 10 + i, last=i == 4) for i in range(5)]
    words += [rec(3, 3, 7), rec(4, 4, 8, last=True), EMPTY]
    frames = decode_records(words)
    for capacity in (0, 1, 2, 5):
        got = c_stream(c_programs, tmp_path, words, 3, capacity)
        assert got == render(frames, capacity), f"capacity {capacity}"
    assert "truncated" in c_stream(c_programs, tmp_path, words, 0, 2)

    program = c_programs["decode_records"]
    full = render(frames) + "result 0 frames 3 corners 7\n"
    assert run_c(program, tmp_path, words, "--all", 3, 7) == full
    got = run_c(program, tmp_path, words, "--all", 1, 7)
    assert got == render(frames[:1]) + "result -2 frames 3 corners 7\n"
    got = run_c(program, tmp_path, words, "--all", 3, 6)
    lines = got.splitlines()
    assert lines[-1] == "result -2 frames 3 corners 7"
    assert "corners 2 stored 1 flags truncated" in lines[6]  # the second frame lost one
    got = run_c(program, tmp_path, words, "--all", 0, 0)
    assert got == "result -2 frames 3 corners 7\n"


@pytest.mark.parametrize(
    "words",
    [
        [rec(empty=True), rec(3, 3, 9, last=True)],  # EMPTY without LAST
        [rec(3, 0, 0, last=True, empty=True)],  # EMPTY with a field set
        [rec(area=1, last=True, empty=True)],  # EMPTY with an AREA
        [rec(3, 3, 9), EMPTY],  # EMPTY after a corner, without OVERFLOW
        [rec(last=True, empty=True, aborted=True)],  # EMPTY and ABORTED
        [rec(3, 3, 9, aborted=True), rec(4, 4, 9, last=True)],  # ABORTED without LAST
        [rec(3, 3, 9, overflow=True), rec(4, 4, 9, last=True)],  # OVERFLOW without LAST
    ],
    ids=[
        "empty-not-last",
        "empty-fields",
        "empty-area",
        "empty-after",
        "empty-aborted",
        "aborted",
        "overflow",
    ],
)
def test_malformed_records(words, c_programs, tmp_path):
    """Flagged in their frame; the next LAST ends it and the next frame is clean."""
    frames = decoded(c_programs, tmp_path, [*words, rec(5, 5, 50, last=True)])
    assert frames[0].malformed and frames[0].complete
    assert frames[-1].corners == [(5, 5, 50)] and not frames[-1].malformed


def test_areas(c_programs, tmp_path):
    """The region NMS's AREA (bits 63:53, saturating at 2047) with each corner, whatever
    the pieces; 0 for a record without it; the EMPTY record has none."""
    assert (regs.REC_AREA.lsb, regs.REC_AREA.width) == (53, 11)
    assert regs.REC_AREA.lsb + regs.REC_AREA.width == 64  # AREA ends at bit 63
    words = [
        rec(3, 4, 5, area=1),
        rec(0xFFFF, 0xFFFF, 0xFFF, area=2047),  # every field at its largest
        rec(6, 7, 8),  # AREA 0: another NMS
        rec(9, 10, 11, area=1024, last=True),
        EMPTY,
        rec(12, 13, 14, area=2, last=True, aborted=True),
    ]
    first, empty, aborted = decoded(c_programs, tmp_path, words, chunks=(0, 1, 2, 4))
    assert first.corners == [(3, 4, 5), (0xFFFF, 0xFFFF, 0xFFF), (6, 7, 8), (9, 10, 11)]
    assert first.areas == [1, 2047, 0, 1024] and first.flags == []
    assert empty.flags == ["empty"] and empty.corners == [] and empty.areas == []
    assert aborted.flags == ["aborted"] and aborted.areas == [2]
    # A corner's AREA stays with it in every frame, whatever the other fields.
    (orb,) = decoded(c_programs, tmp_path, orb_record(40, 31, 27, 1, bytes(32), last=True))
    assert orb.areas == [0]
    got = c_stream(c_programs, tmp_path, words, 0)
    assert "65535 65535 4095 area 2047\n" in got and "6 7 8\n" in got


def orb_record(x, y, score, angle_bits: int, descriptor: bytes, **flags) -> list[int]:
    """The REC_ORB_BEATS words of one keypoint in record format 2."""
    payload = [0] * (regs.REC_ORB_BEATS - 1)
    payload[regs.REC_ANGLE_BEAT - 1] = angle_bits << regs.REC_ANGLE.lsb
    for b in range(regs.REC_DESCRIPTOR_BEATS):
        chunk = descriptor[8 * b : 8 * b + 8]
        payload[regs.REC_DESCRIPTOR_BEAT - 1 + b] = int.from_bytes(chunk, "little")
    return [rec(x, y, score, orb=True, **flags), *payload]


def test_orb_records(c_programs, tmp_path):
    """Record format 2: each keypoint's angle and 32 descriptor bytes, whatever the pieces;
    the EMPTY record stays one word; the frame ends after its LAST record's payload."""
    desc = [bytes(range(32)), bytes(range(255, 223, -1))]
    words = orb_record(40, 31, 27, 0x43340000, desc[0])  # 180.0 degrees
    words += orb_record(33, 50, 90, 0x3F800000, desc[1], last=True)  # 1.0
    words += [EMPTY]
    words += orb_record(31, 31, 20, 0x42B40000, desc[0], last=True, aborted=True)
    first, empty, aborted = decoded(c_programs, tmp_path, words, chunks=(0, 1, 2, 5, 6, 7))
    assert first.orb and first.corners == [(40, 31, 27), (33, 50, 90)]
    assert first.angle_bits == [0x43340000, 0x3F800000] and first.descriptors == desc
    assert (first.records, first.words, first.flags) == (2, 12, ["orb"])
    assert empty.flags == ["empty"] and (empty.records, empty.words) == (1, 1)
    assert aborted.flags == ["aborted", "orb"] and aborted.angle_bits == [0x42B40000]
    # A stream cut in a payload: the frame is incomplete, its payload zero.
    (tail,) = decoded(c_programs, tmp_path, words[:9])
    assert tail.flags == ["incomplete", "orb"] and tail.angle_bits == [0x43340000, 0]
    assert tail.descriptors == [desc[0], bytes(32)] and tail.words == 9


@pytest.mark.parametrize(
    "words",
    [
        [rec(last=True, empty=True, orb=True), *[0] * 5],  # ORB with EMPTY
        [*orb_record(40, 40, 9, 1, bytes(32)), rec(41, 40, 9, last=True)],  # mixed
        [rec(41, 40, 9), *orb_record(40, 40, 9, 1, bytes(32), last=True)],  # mixed
    ],
    ids=["orb-empty", "orb-then-plain", "plain-then-orb"],
)
def test_malformed_orb_records(words, c_programs, tmp_path):
    frames = decoded(c_programs, tmp_path, [*words, rec(5, 5, 50, last=True)])
    assert frames[0].malformed and frames[0].complete
    assert frames[-1].corners == [(5, 5, 50)] and not frames[-1].malformed


def test_python_rejects_words_out_of_range():
    for word in (-1, 1 << 64):
        with pytest.raises(ValueError):
            RecordDecoder().feed([word])


def test_random_words(rng, c_programs, tmp_path):
    """Random streams: both decoders agree, whatever the pieces and the storage."""
    for _ in range(4):
        n = 1500
        words = rng.integers(0, 1 << 16, (n, 3), dtype=np.uint64)
        words = words[:, 0] | words[:, 1] << np.uint64(16) | words[:, 2] << np.uint64(32)
        # AREA on about half the records (the region NMS's streams), 2047 among them
        area = rng.integers(0, regs.REC_AREA.mask >> regs.REC_AREA.lsb, n, endpoint=True)
        area[rng.random(n) < 0.5] = 0
        area[rng.random(n) < 0.02] = 2047
        words |= area.astype(np.uint64) << np.uint64(regs.REC_AREA.lsb)
        for fld, p in [
            (regs.REC_LAST, 0.2),
            (regs.REC_EMPTY, 0.1),
            (regs.REC_ABORTED, 0.05),
            (regs.REC_OVERFLOW, 0.05),
            (regs.REC_ORB, 0.03 if _ % 2 else 0.9),  # payload words follow (format 2)
        ]:
            words |= (rng.random(n) < p).astype(np.uint64) << np.uint64(fld.lsb)
        # a few clean EMPTY records, so that EMPTY frames are frequent
        words[rng.random(n) < 0.05] = EMPTY
        words = [int(w) for w in words]
        frames = decode_records(words)
        chunk, capacity = int(rng.integers(1, 40)), int(rng.integers(0, 6))
        got = c_stream(c_programs, tmp_path, words, chunk, capacity)
        assert got == render(frames, capacity), f"chunk {chunk}, capacity {capacity}"
        assert render(py_stream(words, chunk)) == render(frames)
