/* Unit tests of sw/fastnms.c that need no simulation: the register helpers against a
 * fake register file that checks every access, and the decoder's argument errors.
 * Built and run by sw/tests/test_sw_regs.py; prints "ok N checks" and exits 0, or
 * prints each failed check and exits 1. */
#include <stdio.h>
#include <string.h>

#include "fastnms.h"

static int checks, failures;

#define CHECK(cond)                                                                   \
    do {                                                                              \
        checks++;                                                                     \
        if (!(cond)) {                                                                \
            failures++;                                                               \
            printf("FAIL %s:%d: %s\n", __FILE__, __LINE__, #cond);                     \
        }                                                                             \
    } while (0)

/* ---- the fake register file ---------------------------------------------------- */

#define REGS 17u
#define LOG 64u

struct fake {
    uint32_t reg[REGS];     /* what reads return, by offset / 4 */
    uint32_t log_offset[LOG];
    uint32_t log_value[LOG];
    unsigned writes;        /* writes so far (the first LOG are logged) */
    unsigned reads;
    unsigned cmd_reads;
    unsigned reset_reads;   /* CMD reads that show SOFT_RESET = 1 after a keyed soft reset */
    unsigned busy;          /* what is left of them */
    unsigned bad_accesses;  /* unaligned or outside the map */
};

static uint32_t sticky(void)
{
    return FASTNMS_STATUS_STICKY;
}

static bool valid_offset(uint32_t offset)
{
    return offset % 4u == 0u && offset <= FASTNMS_MIN_AREA_OFFSET;
}

static uint32_t fake_read(void *ctx, uint32_t offset)
{
    struct fake *f = ctx;
    f->reads++;
    if (!valid_offset(offset)) {
        f->bad_accesses++;
        return 0;
    }
    if (offset == FASTNMS_CMD_OFFSET) {
        f->cmd_reads++;
        if (f->busy > 0u) {
            f->busy--;
            return FASTNMS_CMD_SOFT_RESET_MASK;
        }
        return 0;
    }
    return f->reg[offset / 4u];
}

static void fake_write(void *ctx, uint32_t offset, uint32_t value)
{
    struct fake *f = ctx;
    if (f->writes < LOG) {
        f->log_offset[f->writes] = offset;
        f->log_value[f->writes] = value;
    }
    f->writes++;
    if (!valid_offset(offset)) {
        f->bad_accesses++;
        return;
    }
    switch (offset) {
    case FASTNMS_CMD_OFFSET:
        if ((value & FASTNMS_CMD_KEY_MASK) >> FASTNMS_CMD_KEY_SHIFT == 0x5Au &&
            (value & FASTNMS_CMD_SOFT_RESET_MASK))
            f->busy = f->reset_reads;
        break;
    case FASTNMS_STATUS_OFFSET:
        f->reg[offset / 4u] &= ~(value & sticky());
        break;
    default:
        f->reg[offset / 4u] = value;
    }
}

/* A core as after reset: 0.2.x, 640x480, 512-record FIFO, opencv + region4. */
static void fake_init(struct fake *f, struct fastnms_regs_io *io)
{
    memset(f, 0, sizeof *f);
    f->reg[FASTNMS_ID_OFFSET / 4u] = FASTNMS_ID_MAGIC_RESET;
    f->reg[FASTNMS_VERSION_OFFSET / 4u] = FASTNMS_VERSION_MAJOR_RESET << 16 |
                                          FASTNMS_VERSION_MINOR_RESET << 8 | 3u;
    f->reg[FASTNMS_CTRL_OFFSET / 4u] = FASTNMS_CTRL_ENABLE_MASK;
    f->reg[FASTNMS_MAX_SIZE_OFFSET / 4u] = 480u << FASTNMS_MAX_SIZE_HEIGHT_SHIFT | 640u;
    f->reg[FASTNMS_BUILD_OFFSET / 4u] =
        FASTNMS_BUILD_SCORE_VIDEO_MASK | 4u << FASTNMS_BUILD_MAX_PER_CELL_SHIFT | 512u;
    f->reg[FASTNMS_MODE_OFFSET / 4u] = FASTNMS_MODE_NMS_REGION4 << FASTNMS_MODE_NMS_SHIFT |
                                       FASTNMS_MODE_SCORE_OPENCV | 4u << FASTNMS_MODE_PPC_SHIFT;
    f->reset_reads = 3;
    io->read = fake_read;
    io->write = fake_write;
    io->ctx = f;
}

static uint32_t reg(const struct fake *f, uint32_t offset)
{
    return f->reg[offset / 4u];
}

/* ---- register helpers ------------------------------------------------------------ */

static void test_probe(void)
{
    struct fake f;
    struct fastnms_regs_io io;
    struct fastnms_info info;

    fake_init(&f, &io);
    memset(&info, 0xA5, sizeof info);
    CHECK(fastnms_probe(&io, &info) == FASTNMS_OK);
    CHECK(info.major == FASTNMS_VERSION_MAJOR_RESET && info.minor == FASTNMS_VERSION_MINOR_RESET);
    CHECK(info.patch == 3u);
    CHECK(info.max_width == 640u && info.max_height == 480u);
    CHECK(info.fifo_depth == 512u && info.score_video);
    CHECK(info.score == FASTNMS_MODE_SCORE_OPENCV && info.nms == FASTNMS_MODE_NMS_REGION4);
    CHECK(info.ppc == 4u && info.max_per_cell == 4u);
    CHECK(f.writes == 0u);
    CHECK(fastnms_probe(&io, NULL) == FASTNMS_OK);

    f.reg[FASTNMS_ID_OFFSET / 4u] = 0xDEADBEEFu;
    CHECK(fastnms_probe(&io, &info) == FASTNMS_ERR_ID);
    fake_init(&f, &io);
    f.reg[FASTNMS_VERSION_OFFSET / 4u] = (FASTNMS_VERSION_MINOR_RESET + 1u) << 8;
    CHECK(fastnms_probe(&io, &info) == FASTNMS_ERR_VERSION);
    f.reg[FASTNMS_VERSION_OFFSET / 4u] = (FASTNMS_VERSION_MAJOR_RESET + 1u) << 16 |
                                         FASTNMS_VERSION_MINOR_RESET << 8;
    CHECK(fastnms_probe(&io, &info) == FASTNMS_ERR_VERSION);
    CHECK(f.bad_accesses == 0u);
}

static void test_budget(void)
{
    struct fake f;
    struct fastnms_regs_io io;
    uint32_t cell;

    fake_init(&f, &io); /* BUILD.MAX_PER_CELL = 4 */
    for (cell = 16u; cell <= 256u; cell *= 2u) {
        CHECK(fastnms_set_budget(&io, cell, 4u) == FASTNMS_OK);
        CHECK(reg(&f, FASTNMS_BUDGET_OFFSET) == (cell << 16 | 4u));
    }
    CHECK(fastnms_set_budget(&io, 16u, 0u) == FASTNMS_OK);
    CHECK(reg(&f, FASTNMS_BUDGET_OFFSET) == 16u << 16);
    f.writes = 0;
    CHECK(fastnms_set_budget(&io, 16u, 5u) == FASTNMS_ERR_RANGE);
    CHECK(fastnms_set_budget(&io, 8u, 1u) == FASTNMS_ERR_RANGE);
    CHECK(fastnms_set_budget(&io, 48u, 1u) == FASTNMS_ERR_RANGE);
    CHECK(fastnms_set_budget(&io, 512u, 1u) == FASTNMS_ERR_RANGE);
    CHECK(fastnms_set_budget(&io, 0u, 1u) == FASTNMS_ERR_RANGE);
    CHECK(f.writes == 0u);
    /* A build without the budget takes only K = 0. */
    f.reg[FASTNMS_BUILD_OFFSET / 4u] = 512u;
    CHECK(fastnms_set_budget(&io, 64u, 1u) == FASTNMS_ERR_RANGE);
    CHECK(fastnms_set_budget(&io, 64u, 0u) == FASTNMS_OK);
    CHECK(f.bad_accesses == 0u);
}

static void test_min_area(void)
{
    struct fake f;
    struct fastnms_regs_io io;

    fake_init(&f, &io);
    CHECK(FASTNMS_AREA_MAX == 2047u);
    CHECK(fastnms_set_min_area(&io, 5u) == FASTNMS_OK);
    CHECK(reg(&f, FASTNMS_MIN_AREA_OFFSET) == 5u);
    CHECK(fastnms_set_min_area(&io, 2047u) == FASTNMS_OK);
    CHECK(reg(&f, FASTNMS_MIN_AREA_OFFSET) == 2047u);
    CHECK(fastnms_set_min_area(&io, 0u) == FASTNMS_OK);
    CHECK(reg(&f, FASTNMS_MIN_AREA_OFFSET) == 0u);
    CHECK(f.writes == 3u && f.reads == 0u);
    CHECK(fastnms_set_min_area(&io, 2048u) == FASTNMS_ERR_RANGE);
    CHECK(fastnms_set_min_area(&io, 0xFFFFFFFFu) == FASTNMS_ERR_RANGE);
    CHECK(f.writes == 3u);
    CHECK(fastnms_set_min_area(NULL, 5u) == FASTNMS_ERR_ARG);
    CHECK(f.bad_accesses == 0u);
}

static void test_configure(void)
{
    struct fake f;
    struct fastnms_regs_io io;

    fake_init(&f, &io);
    CHECK(fastnms_configure(&io, 320, 240, 20) == FASTNMS_OK);
    CHECK(f.writes == 3u);
    CHECK(reg(&f, FASTNMS_WIDTH_OFFSET) == 320u && reg(&f, FASTNMS_HEIGHT_OFFSET) == 240u);
    CHECK(reg(&f, FASTNMS_THRESHOLD_OFFSET) == 20u);
    /* The limits themselves are taken. */
    CHECK(fastnms_configure(&io, 640, 480, 255) == FASTNMS_OK);
    CHECK(reg(&f, FASTNMS_WIDTH_OFFSET) == 640u && reg(&f, FASTNMS_HEIGHT_OFFSET) == 480u);
    CHECK(reg(&f, FASTNMS_THRESHOLD_OFFSET) == 255u);
    CHECK(fastnms_configure(&io, 7, 7, 0) == FASTNMS_OK);
    CHECK(reg(&f, FASTNMS_WIDTH_OFFSET) == 7u && reg(&f, FASTNMS_THRESHOLD_OFFSET) == 0u);
    /* Out of range: an error and nothing written (the core would clamp it). */
    f.writes = 0;
    CHECK(fastnms_configure(&io, 641, 480, 20) == FASTNMS_ERR_RANGE);
    CHECK(fastnms_configure(&io, 640, 481, 20) == FASTNMS_ERR_RANGE);
    CHECK(fastnms_configure(&io, 6, 480, 20) == FASTNMS_ERR_RANGE);
    CHECK(fastnms_configure(&io, 640, 6, 20) == FASTNMS_ERR_RANGE);
    CHECK(fastnms_configure(&io, 640, 480, 256) == FASTNMS_ERR_RANGE);
    CHECK(fastnms_configure(&io, 0x10000u + 320u, 240, 20) == FASTNMS_ERR_RANGE);
    CHECK(fastnms_configure(&io, 320, 240, 0xFFFFFFFFu) == FASTNMS_ERR_RANGE);
    CHECK(f.writes == 0u);
    CHECK(reg(&f, FASTNMS_WIDTH_OFFSET) == 7u);
    /* A smaller build's MAX_SIZE is honoured. */
    f.reg[FASTNMS_MAX_SIZE_OFFSET / 4u] = 1080u << 16 | 1920u;
    CHECK(fastnms_configure(&io, 1920, 1080, 20) == FASTNMS_OK);
    CHECK(fastnms_configure(&io, 1921, 1080, 20) == FASTNMS_ERR_RANGE);
    CHECK(f.bad_accesses == 0u);
}

static void test_ctrl(void)
{
    struct fake f;
    struct fastnms_regs_io io;

    fake_init(&f, &io);
    f.reg[FASTNMS_CTRL_OFFSET / 4u] = FASTNMS_CTRL_ENABLE_MASK | FASTNMS_CTRL_IRQ_ENABLE_MASK;
    CHECK(fastnms_set_live(&io, true) == FASTNMS_OK);
    CHECK(f.writes == 1u && f.log_offset[0] == FASTNMS_CTRL_OFFSET);
    CHECK(reg(&f, FASTNMS_CTRL_OFFSET) == (FASTNMS_CTRL_ENABLE_MASK |
                                           FASTNMS_CTRL_IRQ_ENABLE_MASK |
                                           FASTNMS_CTRL_LIVE_MASK));
    CHECK(fastnms_set_live(&io, false) == FASTNMS_OK);
    CHECK(reg(&f, FASTNMS_CTRL_OFFSET) ==
          (FASTNMS_CTRL_ENABLE_MASK | FASTNMS_CTRL_IRQ_ENABLE_MASK));
    /* Reserved bits (bit 1, the old soft reset) are never written back. */
    f.reg[FASTNMS_CTRL_OFFSET / 4u] = 0xFFFFFFF6u; /* IRQ_ENABLE 1, ENABLE 0, LIVE 0 */
    CHECK(fastnms_set_live(&io, true) == FASTNMS_OK);
    CHECK(reg(&f, FASTNMS_CTRL_OFFSET) == (FASTNMS_CTRL_IRQ_ENABLE_MASK |
                                           FASTNMS_CTRL_LIVE_MASK));
    CHECK(fastnms_set_enable(&io, true) == FASTNMS_OK);
    CHECK(reg(&f, FASTNMS_CTRL_OFFSET) == (FASTNMS_CTRL_ENABLE_MASK |
                                           FASTNMS_CTRL_IRQ_ENABLE_MASK |
                                           FASTNMS_CTRL_LIVE_MASK));
    CHECK(fastnms_set_irq_enable(&io, false) == FASTNMS_OK);
    CHECK(reg(&f, FASTNMS_CTRL_OFFSET) == (FASTNMS_CTRL_ENABLE_MASK | FASTNMS_CTRL_LIVE_MASK));
    CHECK(fastnms_set_enable(&io, false) == FASTNMS_OK);
    CHECK(reg(&f, FASTNMS_CTRL_OFFSET) == FASTNMS_CTRL_LIVE_MASK);
    CHECK(f.bad_accesses == 0u);
}

static void test_soft_reset(void)
{
    struct fake f;
    struct fastnms_regs_io io;

    fake_init(&f, &io);
    CHECK(fastnms_soft_reset(&io, 0) == FASTNMS_OK);
    CHECK(f.writes == 1u && f.log_offset[0] == FASTNMS_CMD_OFFSET);
    CHECK(f.log_value[0] == 0x5A000001u);
    CHECK(f.cmd_reads == 4u); /* 3 busy, then done */
    /* A core that never finishes: exactly max_polls reads, then a timeout. */
    fake_init(&f, &io);
    f.reset_reads = 1000000u;
    CHECK(fastnms_soft_reset(&io, 25) == FASTNMS_ERR_TIMEOUT);
    CHECK(f.cmd_reads == 25u && f.writes == 1u);
    fake_init(&f, &io);
    f.reset_reads = 1000000u;
    CHECK(fastnms_soft_reset(&io, 0) == FASTNMS_ERR_TIMEOUT);
    CHECK(f.cmd_reads == FASTNMS_SOFT_RESET_POLLS);
    /* Done within the limit. */
    fake_init(&f, &io);
    f.reset_reads = 24;
    CHECK(fastnms_soft_reset(&io, 25) == FASTNMS_OK);
    CHECK(f.bad_accesses == 0u);
}

static void test_status_and_counters(void)
{
    struct fake f;
    struct fastnms_regs_io io;
    struct fastnms_counters c;

    fake_init(&f, &io);
    f.reg[FASTNMS_STATUS_OFFSET / 4u] = FASTNMS_STATUS_BUSY_MASK | FASTNMS_STATUS_FRAME_DONE_MASK |
                                        FASTNMS_STATUS_OVERFLOW_MASK |
                                        FASTNMS_STATUS_EOL_LATE_MASK;
    CHECK(fastnms_status(&io) == reg(&f, FASTNMS_STATUS_OFFSET));
    CHECK(fastnms_clear_status(&io, FASTNMS_STATUS_FRAME_DONE_MASK) == FASTNMS_OK);
    CHECK(f.writes == 1u && f.log_value[0] == FASTNMS_STATUS_FRAME_DONE_MASK);
    CHECK(fastnms_status(&io) == (FASTNMS_STATUS_BUSY_MASK | FASTNMS_STATUS_OVERFLOW_MASK |
                                  FASTNMS_STATUS_EOL_LATE_MASK));
    /* Only sticky bits are written: BUSY and the unused bits are masked off. */
    CHECK(fastnms_clear_status(&io, 0xFFFFFFFFu) == FASTNMS_OK);
    CHECK(f.writes == 2u && f.log_value[1] == 0x7FEu);
    CHECK(fastnms_status(&io) == FASTNMS_STATUS_BUSY_MASK);
    CHECK(fastnms_clear_status(&io, FASTNMS_STATUS_BUSY_MASK) == FASTNMS_OK);
    CHECK(f.writes == 2u);

    f.reg[FASTNMS_CORNER_COUNT_OFFSET / 4u] = 11;
    f.reg[FASTNMS_FRAME_COUNT_OFFSET / 4u] = 22;
    f.reg[FASTNMS_DROPPED_OFFSET / 4u] = 33;
    f.reg[FASTNMS_INPUT_STALLS_OFFSET / 4u] = 0xFFFFFFFFu;
    CHECK(fastnms_read_counters(&io, &c) == FASTNMS_OK);
    CHECK(c.corner_count == 11u && c.frame_count == 22u && c.dropped == 33u);
    CHECK(c.input_stalls == 0xFFFFFFFFu);
    CHECK(f.bad_accesses == 0u);
}

static void test_bad_io(void)
{
    struct fake f;
    struct fastnms_regs_io io, broken;
    struct fastnms_counters c;

    fake_init(&f, &io);
    broken = io;
    broken.write = NULL;
    CHECK(fastnms_probe(NULL, NULL) == FASTNMS_ERR_ARG);
    CHECK(fastnms_probe(&broken, NULL) == FASTNMS_ERR_ARG);
    CHECK(fastnms_configure(&broken, 320, 240, 20) == FASTNMS_ERR_ARG);
    CHECK(fastnms_set_live(NULL, true) == FASTNMS_ERR_ARG);
    CHECK(fastnms_soft_reset(&broken, 10) == FASTNMS_ERR_ARG);
    CHECK(fastnms_status(NULL) == 0u);
    CHECK(fastnms_clear_status(NULL, 2) == FASTNMS_ERR_ARG);
    CHECK(fastnms_read_counters(&io, NULL) == FASTNMS_ERR_ARG);
    CHECK(fastnms_read_counters(NULL, &c) == FASTNMS_ERR_ARG);
    CHECK(f.reads == 0u && f.writes == 0u);
}

/* ---- decoder arguments ----------------------------------------------------------- */

static void test_decoder_arguments(void)
{
    struct fastnms_decoder dec;
    struct fastnms_frame frame;
    struct fastnms_corner corners[2];
    const uint64_t word = FASTNMS_REC_LAST_MASK | 5u;
    size_t used = 99, n_frames = 99, n_corners = 99;

    CHECK(fastnms_decoder_init(NULL, corners, 2) == FASTNMS_ERR_ARG);
    CHECK(fastnms_decoder_init(&dec, NULL, 2) == FASTNMS_ERR_ARG);
    CHECK(fastnms_decoder_init(&dec, NULL, 0) == FASTNMS_OK);
    CHECK(fastnms_decode(&dec, NULL, 1, &used, &frame) == FASTNMS_ERR_ARG);
    CHECK(fastnms_decode(&dec, &word, 1, NULL, &frame) == FASTNMS_ERR_ARG);
    CHECK(fastnms_decode(&dec, &word, 1, &used, NULL) == FASTNMS_ERR_ARG);
    CHECK(fastnms_decode(NULL, &word, 1, &used, &frame) == FASTNMS_ERR_ARG);
    CHECK(fastnms_decode(&dec, NULL, 0, &used, &frame) == FASTNMS_OK && used == 0u);
    CHECK(fastnms_decoder_flush(&dec, &frame) == FASTNMS_OK);
    CHECK(fastnms_decoder_flush(NULL, &frame) == FASTNMS_ERR_ARG);
    CHECK(fastnms_decoder_pending(NULL) == 0u);
    /* No storage: corners counted, none stored. */
    CHECK(fastnms_decode(&dec, &word, 1, &used, &frame) == FASTNMS_FRAME && used == 1u);
    CHECK(frame.corners == 1u && frame.stored == 0u);
    CHECK(frame.flags == FASTNMS_FRAME_TRUNCATED);

    CHECK(fastnms_decode_all(NULL, 1, corners, 2, NULL, 0, &n_frames, &n_corners) ==
          FASTNMS_ERR_ARG);
    CHECK(fastnms_decode_all(&word, 1, NULL, 2, NULL, 0, &n_frames, &n_corners) ==
          FASTNMS_ERR_ARG);
    CHECK(fastnms_decode_all(&word, 1, corners, 2, NULL, 1, &n_frames, &n_corners) ==
          FASTNMS_ERR_ARG);
    CHECK(fastnms_decode_all(&word, 1, corners, 2, NULL, 0, NULL, &n_corners) ==
          FASTNMS_ERR_ARG);
    CHECK(fastnms_decode_all(NULL, 0, NULL, 0, NULL, 0, &n_frames, &n_corners) == FASTNMS_OK);
    CHECK(n_frames == 0u && n_corners == 0u);
    CHECK(fastnms_decode_all(&word, 1, NULL, 0, NULL, 0, &n_frames, &n_corners) ==
          FASTNMS_ERR_NO_SPACE);
    CHECK(n_frames == 1u && n_corners == 1u);

    CHECK(strcmp(fastnms_strerror(FASTNMS_ERR_TIMEOUT), "soft reset did not finish") == 0);
    CHECK(strcmp(fastnms_strerror(12345), "unknown") == 0);
}

/* A record's AREA (bits 63:53), 2047 the largest; the EMPTY record with an AREA is
 * malformed. */
static void test_decoder_area(void)
{
    struct fastnms_decoder dec;
    struct fastnms_frame frame;
    struct fastnms_corner corners[2];
    const uint64_t words[3] = {
        (uint64_t)7u << FASTNMS_REC_AREA_SHIFT | (uint64_t)9u << FASTNMS_REC_SCORE_SHIFT |
            4u << FASTNMS_REC_Y_SHIFT | 3u,
        (uint64_t)2047u << FASTNMS_REC_AREA_SHIFT | FASTNMS_REC_LAST_MASK | 5u,
        (uint64_t)1u << FASTNMS_REC_AREA_SHIFT | FASTNMS_REC_EMPTY_MASK | FASTNMS_REC_LAST_MASK,
    };
    size_t used = 0;

    CHECK(fastnms_decoder_init(&dec, corners, 2) == FASTNMS_OK);
    CHECK(fastnms_decode(&dec, words, 3, &used, &frame) == FASTNMS_FRAME && used == 2u);
    CHECK(frame.flags == 0u && frame.stored == 2u);
    CHECK(frame.corner[0].x == 3u && frame.corner[0].y == 4u && frame.corner[0].score == 9u);
    CHECK(frame.corner[0].area == 7u && frame.corner[1].area == FASTNMS_AREA_MAX);
    CHECK(frame.corner[1].x == 5u && frame.corner[1].score == 0u);
    CHECK(fastnms_decode(&dec, words + 2, 1, &used, &frame) == FASTNMS_FRAME);
    CHECK(frame.flags == (FASTNMS_FRAME_EMPTY | FASTNMS_FRAME_MALFORMED));
}

int main(void)
{
    test_probe();
    test_configure();
    test_budget();
    test_min_area();
    test_ctrl();
    test_soft_reset();
    test_status_and_counters();
    test_bad_io();
    test_decoder_arguments();
    test_decoder_area();
    if (failures) {
        printf("%d of %d checks failed\n", failures, checks);
        return 1;
    }
    printf("ok %d checks\n", checks);
    return 0;
}
