/* fastnms: software for the fastnms_axi IP core.
 *
 * - The record decoder: turns the 64-bit corner records of m_axis_corners (as an
 *   AXI DMA writes them to memory) into frames of keypoints, fed one buffer at a
 *   time (a frame may span several buffers), or all at once; with ORB (record
 *   format 2) each keypoint's angle and descriptor too.
 * - The register helpers: probe, frame set-up, live mode, soft reset, status and
 *   counters, through a register accessor the caller supplies (memory-mapped
 *   I/O, Linux UIO, a simulator, a test double).
 *
 * C99, no operating system and no C library: only <stdint.h>, <stddef.h> and
 * <stdbool.h>. Nothing is allocated; no function keeps a pointer it was given
 * except the decoder's corner storage. See sw/README.md.
 *
 * Record format and register map: fastnms_regs.h (generated from
 * rtl/top/fastnms_regs.toml) and docs/fastnms_axi.md.
 */
#ifndef FASTNMS_H
#define FASTNMS_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

#include "fastnms_regs.h"

#ifdef __cplusplus
extern "C" {
#endif

/* ---- return codes ------------------------------------------------------------ */

#define FASTNMS_FRAME         1  /* fastnms_decode, _flush: a frame is delivered */
#define FASTNMS_OK            0
#define FASTNMS_ERR_ARG       -1 /* a NULL pointer or an impossible argument */
#define FASTNMS_ERR_NO_SPACE  -2 /* an output array is too small (fastnms_decode_all) */
#define FASTNMS_ERR_ID        -3 /* ID is not 0x46415354: no fastnms core at this address */
#define FASTNMS_ERR_VERSION   -4 /* the core's register map is not the one of fastnms_regs.h */
#define FASTNMS_ERR_RANGE     -5 /* a size or threshold outside what the core takes */
#define FASTNMS_ERR_TIMEOUT   -6 /* the soft reset did not finish within the polls allowed */

/* A short English description of a return code ("unknown" for others). */
const char *fastnms_strerror(int code);

/* ---- the record decoder ------------------------------------------------------ */

struct fastnms_corner {
    uint16_t x;     /* column, 3 .. WIDTH-4 */
    uint16_t y;     /* row, 3 .. HEIGHT-4 */
    uint16_t score; /* 8 bits (opencv) or 12 bits (sad) */
    uint16_t area;  /* region NMS: the region's corner pixels, saturating at 2047
                       (FASTNMS_AREA_MAX); 0 with the other NMS */
};

/* The largest AREA of a record and MIN_AREA (11 bits). */
#define FASTNMS_AREA_MAX (FASTNMS_MIN_AREA_VALUE_MASK >> FASTNMS_MIN_AREA_VALUE_SHIFT)

/* A keypoint's ORB payload (record format 2, a build with DESCRIPTOR = "orb"). */
struct fastnms_orb {
    uint32_t angle_bits;    /* the angle in degrees, IEEE-754 float32 bits (cv2 KeyPoint.angle) */
    uint8_t descriptor[32]; /* the descriptor, cv2.ORB's 32 bytes in order */
};

/* fastnms_frame.flags */
#define FASTNMS_FRAME_EMPTY      0x01u /* ended by the EMPTY record: the frame had no corner */
#define FASTNMS_FRAME_ABORTED    0x02u /* a soft reset cut the frame: its corners are incomplete */
#define FASTNMS_FRAME_OVERFLOW   0x04u /* records of this frame, or whole frames before it, were
                                          dropped (CTRL.LIVE = 1) */
#define FASTNMS_FRAME_INCOMPLETE 0x08u /* no LAST record yet (fastnms_decoder_flush) */
#define FASTNMS_FRAME_TRUNCATED  0x10u /* more corners than the storage held: `stored` < `corners` */
#define FASTNMS_FRAME_MALFORMED  0x20u /* a record broke the format (see sw/README.md) */
#define FASTNMS_FRAME_ORB        0x40u /* the frame's records carry ORB payloads (format 2) */
#define FASTNMS_FRAME_ERROR      0x80u /* an internal error reset the pipeline (STATUS bits 10:7):
                                          this frame's records, or whole frames before it, were lost */

struct fastnms_frame {
    uint32_t index;       /* frames delivered by this decoder before this one */
    uint32_t flags;       /* FASTNMS_FRAME_* */
    size_t records;       /* records of the frame, the EMPTY record included */
    size_t words;         /* 64-bit words of the frame (= records without ORB) */
    size_t corners;       /* corners of the frame (its records that are not EMPTY) */
    size_t stored;        /* of them, in `corner` (= corners unless TRUNCATED) */
    uint64_t first_word;  /* position of the frame's first record in the whole stream */
    const struct fastnms_corner *corner; /* the stored corners, in output order; valid
                                            until the next call on the decoder */
    const struct fastnms_orb *orb; /* with ORB storage (fastnms_decoder_set_orb) and
                                      FASTNMS_FRAME_ORB: orb[i] belongs to corner[i] */
};

/* The decoder's state: allocate it anywhere, set it up with fastnms_decoder_init;
 * its members are private. */
struct fastnms_decoder {
    struct fastnms_corner *storage;
    struct fastnms_orb *orb_storage;
    size_t capacity;
    uint32_t index;
    uint32_t flags;
    size_t records;
    size_t words;
    bool frame_orb;      /* the frame's first record has ORB */
    uint8_t payload;     /* ORB words still to come for the record in progress */
    bool payload_last;   /* that record is its frame's last */
    size_t payload_slot; /* its storage index, or SIZE_MAX when not stored */
    struct fastnms_orb payload_orb; /* its payload so far */
    size_t corners;
    size_t stored;
    uint64_t position;   /* words consumed since init */
    uint64_t first_word; /* position of the current frame's first record */
};

/* Set up `dec` with room for `capacity` corners of one frame in `storage`
 * (storage may be NULL when capacity is 0: the corners are then only counted). */
int fastnms_decoder_init(struct fastnms_decoder *dec, struct fastnms_corner *storage,
                         size_t capacity);

/* Record format 2: keep the ORB payload of stored corner i in orb_storage[i] (room
 * for the `capacity` given to fastnms_decoder_init; NULL: not kept). Without it the
 * decoder still reads ORB records (the ORB bit of a record's first word says that
 * REC_ORB_BEATS - 1 payload words follow), it only skips their payload. In a frame
 * whose first record has ORB (FASTNMS_FRAME_ORB) every stored corner has an entry;
 * a corner without a complete payload (a malformed frame, or one cut off by the end
 * of the stream) has zeros. */
int fastnms_decoder_set_orb(struct fastnms_decoder *dec, struct fastnms_orb *orb_storage);

/* Decode words[0 .. count-1], stopping after the first frame that ends there.
 * Returns FASTNMS_FRAME: *frame is the frame, *consumed the words used (the
 * frame's LAST record is the last of them; call again with the rest);
 * FASTNMS_OK: all `count` words were used and no frame ended (a frame may be in
 * progress: its corners are kept for the next call); FASTNMS_ERR_ARG.
 * words may be NULL when count is 0. A frame with more corners than the
 * storage holds is delivered with FASTNMS_FRAME_TRUNCATED. */
int fastnms_decode(struct fastnms_decoder *dec, const uint64_t *words, size_t count,
                   size_t *consumed, struct fastnms_frame *frame);

/* End of the stream: the frame in progress, if any, is delivered with
 * FASTNMS_FRAME_INCOMPLETE (FASTNMS_FRAME), else FASTNMS_OK. The decoder then
 * starts a new frame (use it too when records were lost, e.g. a DMA restarted
 * mid-frame). */
int fastnms_decoder_flush(struct fastnms_decoder *dec, struct fastnms_frame *frame);

/* Records of the frame in progress (0 between frames). */
size_t fastnms_decoder_pending(const struct fastnms_decoder *dec);

/* One-shot: every frame of words[0 .. count-1], a last frame without LAST
 * included (FASTNMS_FRAME_INCOMPLETE). The frames' corners follow each other in
 * `corners`. *frame_count and *corner_count are always the numbers of frames and
 * corners found; if they exceed frame_capacity or corner_capacity, the arrays
 * hold what fits (frames whose corners did not fit are TRUNCATED) and the result
 * is FASTNMS_ERR_NO_SPACE. FASTNMS_OK otherwise, or FASTNMS_ERR_ARG. */
int fastnms_decode_all(const uint64_t *words, size_t count, struct fastnms_corner *corners,
                       size_t corner_capacity, struct fastnms_frame *frames,
                       size_t frame_capacity, size_t *frame_count, size_t *corner_count);

/* ---- the register helpers ---------------------------------------------------- */

/* 32-bit register accesses at a byte offset from the core's base address, e.g.
 * `*(volatile uint32_t *)((uintptr_t)ctx + offset)`. */
struct fastnms_regs_io {
    uint32_t (*read)(void *ctx, uint32_t offset);
    void (*write)(void *ctx, uint32_t offset, uint32_t value);
    void *ctx;
};

/* The smallest frame the core takes (WIDTH and HEIGHT). */
#define FASTNMS_MIN_SIZE 7u
/* CMD.KEY: a command acts only with this key in the same write. */
#define FASTNMS_CMD_KEY_UNLOCK 0x5Au
/* The sticky STATUS bits (write 1 to clear). */
#define FASTNMS_STATUS_STICKY                                                             \
    (FASTNMS_STATUS_FRAME_DONE_MASK | FASTNMS_STATUS_EOL_EARLY_MASK |                     \
     FASTNMS_STATUS_EOL_LATE_MASK | FASTNMS_STATUS_SOF_MISSING_MASK |                     \
     FASTNMS_STATUS_SOF_EARLY_MASK | FASTNMS_STATUS_OVERFLOW_MASK |                      \
     FASTNMS_STATUS_INTERNAL)
/* The STATUS bits of the internal errors (each resets the pipeline). */
#define FASTNMS_STATUS_INTERNAL                                                           \
    (FASTNMS_STATUS_ORB_ROWS_MASK | FASTNMS_STATUS_ORB_TAGS_MASK |                        \
     FASTNMS_STATUS_ORB_COUNT_MASK | FASTNMS_STATUS_CONFIG_QUEUE_MASK)
/* Polls of CMD.SOFT_RESET a soft reset is given by default (it takes a few clocks). */
#define FASTNMS_SOFT_RESET_POLLS 1000u

struct fastnms_info {
    uint8_t major, minor, patch; /* VERSION */
    uint16_t max_width;          /* MAX_SIZE */
    uint16_t max_height;
    uint16_t fifo_depth;         /* BUILD.FIFO_DEPTH: corner records buffered */
    bool score_video;            /* BUILD.SCORE_VIDEO: m_axis_score is built */
    uint8_t score;               /* MODE.SCORE: FASTNMS_MODE_SCORE_OPENCV or _SAD */
    uint8_t nms;                 /* MODE.NMS: FASTNMS_MODE_NMS_NONE, _3X3, _REGION4, _REGION8 */
    uint8_t ppc;                 /* MODE.PPC: pixels per beat of the video (1, 2, 4) */
    uint8_t max_per_cell;        /* BUILD.MAX_PER_CELL: largest budget K (0: no budget) */
};

struct fastnms_counters {
    uint32_t corner_count; /* corners of the last completed frame */
    uint32_t frame_count;  /* frames completed since reset (wraps) */
    uint32_t dropped;      /* records dropped in live mode since reset (wraps) */
    uint32_t input_stalls; /* clocks the video input was held since reset (wraps) */
};

/* Check ID and VERSION (same major, and same minor while the major is 0, as
 * fastnms_regs.h); fill *info (may be NULL) from VERSION, MAX_SIZE, BUILD, MODE. */
int fastnms_probe(const struct fastnms_regs_io *io, struct fastnms_info *info);

/* Write WIDTH, HEIGHT and THRESHOLD. A frame takes the values written before
 * its first pixel is accepted: these apply from the first frame that starts
 * after this call returns (the IP never holds the video for them).
 * FASTNMS_ERR_RANGE, and nothing written, unless 7 <= width <=
 * MAX_SIZE.WIDTH, 7 <= height <= MAX_SIZE.HEIGHT and threshold <= 255. */
int fastnms_configure(const struct fastnms_regs_io *io, uint32_t width, uint32_t height,
                      uint32_t threshold);

/* Write BUDGET: at most `per_cell` records per `cell` x `cell` grid cell (the
 * best scores; per_cell 0: every record), applied like fastnms_configure.
 * FASTNMS_ERR_RANGE, and nothing written, unless cell is 16, 32, 64, 128 or 256
 * and per_cell <= BUILD.MAX_PER_CELL (0 in a build without the budget). */
int fastnms_set_budget(const struct fastnms_regs_io *io, uint32_t cell, uint32_t per_cell);

/* Write MIN_AREA: the region NMS drops the regions of fewer than `min_area` corner
 * pixels (0 and 1 keep every region; the other NMS ignore it), applied like
 * fastnms_configure. FASTNMS_ERR_RANGE, and nothing written, unless
 * min_area <= FASTNMS_AREA_MAX. */
int fastnms_set_min_area(const struct fastnms_regs_io *io, uint32_t min_area);

/* CTRL, read-modify-write of one bit, the other CTRL fields kept (reserved bits
 * written as 0). */
int fastnms_set_enable(const struct fastnms_regs_io *io, bool on);
int fastnms_set_irq_enable(const struct fastnms_regs_io *io, bool on);
int fastnms_set_live(const struct fastnms_regs_io *io, bool on);

/* CMD.SOFT_RESET with the key, then poll CMD.SOFT_RESET until 0, at most
 * `max_polls` reads (0: FASTNMS_SOFT_RESET_POLLS); FASTNMS_ERR_TIMEOUT after. */
int fastnms_soft_reset(const struct fastnms_regs_io *io, uint32_t max_polls);

/* STATUS (0 if io is unusable). */
uint32_t fastnms_status(const struct fastnms_regs_io *io);

/* Clear the sticky STATUS bits of `mask` (others in mask are ignored), e.g.
 * FASTNMS_STATUS_FRAME_DONE_MASK to acknowledge the interrupt, or
 * FASTNMS_STATUS_STICKY for all. */
int fastnms_clear_status(const struct fastnms_regs_io *io, uint32_t mask);

/* CORNER_COUNT, FRAME_COUNT, DROPPED, INPUT_STALLS. */
int fastnms_read_counters(const struct fastnms_regs_io *io, struct fastnms_counters *counters);

#ifdef __cplusplus
}
#endif

#endif /* FASTNMS_H */
