/* fastnms: the record decoder and the register helpers (see fastnms.h). */
#include "fastnms.h"

/* A field of a register or record value, shifted down: FIELD(v, STATUS_BUSY). */
#define FIELD(value, name) (((value) & FASTNMS_##name##_MASK) >> FASTNMS_##name##_SHIFT)

const char *fastnms_strerror(int code)
{
    switch (code) {
    case FASTNMS_FRAME:
        return "a frame is delivered";
    case FASTNMS_OK:
        return "ok";
    case FASTNMS_ERR_ARG:
        return "invalid argument";
    case FASTNMS_ERR_NO_SPACE:
        return "output array too small";
    case FASTNMS_ERR_ID:
        return "no fastnms core (wrong ID)";
    case FASTNMS_ERR_VERSION:
        return "unsupported register map version";
    case FASTNMS_ERR_RANGE:
        return "size or threshold out of range";
    case FASTNMS_ERR_TIMEOUT:
        return "soft reset did not finish";
    default:
        return "unknown";
    }
}

/* ---- the record decoder ------------------------------------------------------ */

static size_t saturating_increment(size_t n)
{
    return n == SIZE_MAX ? n : n + 1u;
}

/* The decoder ready for a new frame (corner storage and counters kept). */
static void start_frame(struct fastnms_decoder *dec)
{
    dec->flags = 0;
    dec->records = 0;
    dec->words = 0;
    dec->frame_orb = false;
    dec->payload = 0;
    dec->payload_last = false;
    dec->payload_slot = SIZE_MAX;
    dec->corners = 0;
    dec->stored = 0;
}

int fastnms_decoder_init(struct fastnms_decoder *dec, struct fastnms_corner *storage,
                         size_t capacity)
{
    if (dec == NULL || (storage == NULL && capacity != 0u))
        return FASTNMS_ERR_ARG;
    dec->storage = storage;
    dec->orb_storage = NULL;
    dec->capacity = capacity;
    dec->index = 0;
    dec->position = 0;
    dec->first_word = 0;
    start_frame(dec);
    return FASTNMS_OK;
}

int fastnms_decoder_set_orb(struct fastnms_decoder *dec, struct fastnms_orb *orb_storage)
{
    if (dec == NULL)
        return FASTNMS_ERR_ARG;
    dec->orb_storage = orb_storage;
    return FASTNMS_OK;
}

/* One payload word of an ORB record; true if it ends its frame. */
static bool take_payload(struct fastnms_decoder *dec, uint64_t word)
{
    const unsigned beat = FASTNMS_REC_ORB_BEATS - dec->payload; /* 1 .. ORB_BEATS - 1 */

    struct fastnms_orb *orb = &dec->payload_orb;

    if (dec->payload_slot != SIZE_MAX && dec->orb_storage != NULL) {
        if (beat == FASTNMS_REC_ANGLE_BEAT) {
            orb->angle_bits = (uint32_t)FIELD(word, REC_ANGLE);
        } else if (beat >= FASTNMS_REC_DESCRIPTOR_BEAT &&
                   beat < FASTNMS_REC_DESCRIPTOR_BEAT + FASTNMS_REC_DESCRIPTOR_BEATS) {
            unsigned i;
            for (i = 0; i < 8u; i++)
                orb->descriptor[8u * (beat - FASTNMS_REC_DESCRIPTOR_BEAT) + i] =
                    (uint8_t)(word >> (8u * i));
        }
    }
    dec->payload--;
    if (dec->payload != 0u)
        return false;
    if (dec->payload_slot != SIZE_MAX && dec->orb_storage != NULL && dec->frame_orb)
        dec->orb_storage[dec->payload_slot] = *orb;
    return dec->payload_last;
}

/* The bits of beat 0 that no field uses (0 in every record). */
#define RESERVED_BITS                                                                     \
    (~(FASTNMS_REC_X_MASK | FASTNMS_REC_Y_MASK | FASTNMS_REC_SCORE_MASK |                 \
       FASTNMS_REC_ERROR_MASK | FASTNMS_REC_EMPTY_MASK | FASTNMS_REC_LAST_MASK |          \
       FASTNMS_REC_ABORTED_MASK | FASTNMS_REC_OVERFLOW_MASK | FASTNMS_REC_ORB_MASK |      \
       FASTNMS_REC_AREA_MASK))

/* Add one word to the frame in progress; true if it is the frame's last. */
static bool take_record(struct fastnms_decoder *dec, uint64_t word)
{
    const bool empty = (word & FASTNMS_REC_EMPTY_MASK) != 0u;
    const bool last = (word & FASTNMS_REC_LAST_MASK) != 0u;
    const bool aborted = (word & FASTNMS_REC_ABORTED_MASK) != 0u;
    const bool overflow = (word & FASTNMS_REC_OVERFLOW_MASK) != 0u;
    const bool error = (word & FASTNMS_REC_ERROR_MASK) != 0u;
    const bool orb = (word & FASTNMS_REC_ORB_MASK) != 0u;
    const uint64_t fields = FASTNMS_REC_X_MASK | FASTNMS_REC_Y_MASK | FASTNMS_REC_SCORE_MASK |
                            FASTNMS_REC_AREA_MASK | RESERVED_BITS;

    if (dec->words == 0u)
        dec->first_word = dec->position;
    dec->words = saturating_increment(dec->words);
    if (dec->position != UINT64_MAX)
        dec->position++;
    if (dec->payload != 0u)
        return take_payload(dec, word);

    dec->records = saturating_increment(dec->records);
    if (dec->records == 1u) {
        dec->frame_orb = orb;
        if (orb)
            dec->flags |= FASTNMS_FRAME_ORB;
    } else if (orb != dec->frame_orb)
        dec->flags |= FASTNMS_FRAME_MALFORMED; /* records with and without ORB */
    dec->payload_slot = SIZE_MAX;

    if (empty) {
        /* The only record of its frame, with LAST, all fields 0 (AREA too); records of
         * earlier frames may precede it when their LAST was lost (OVERFLOW, ERROR). */
        dec->flags |= FASTNMS_FRAME_EMPTY;
        if (!last || aborted || (word & fields) != 0u || (dec->records != 1u && !overflow && !error))
            dec->flags |= FASTNMS_FRAME_MALFORMED;
    } else {
        dec->corners = saturating_increment(dec->corners);
        if (dec->stored < dec->capacity) {
            struct fastnms_corner *c = &dec->storage[dec->stored];
            c->x = (uint16_t)FIELD(word, REC_X);
            c->y = (uint16_t)FIELD(word, REC_Y);
            c->score = (uint16_t)FIELD(word, REC_SCORE);
            c->area = (uint16_t)FIELD(word, REC_AREA);
            dec->payload_slot = dec->stored;
            if (dec->frame_orb && dec->orb_storage != NULL) {
                const struct fastnms_orb zero = {0};
                dec->orb_storage[dec->stored] = zero; /* until its payload is complete */
            }
            dec->stored++;
        } else {
            dec->flags |= FASTNMS_FRAME_TRUNCATED;
        }
    }
    if (aborted)
        dec->flags |= FASTNMS_FRAME_ABORTED;
    if (overflow)
        dec->flags |= FASTNMS_FRAME_OVERFLOW;
    if (error)
        dec->flags |= FASTNMS_FRAME_ERROR;
    if ((aborted || overflow || error) && !last)
        dec->flags |= FASTNMS_FRAME_MALFORMED;
    if (orb) {
        if (empty)
            dec->flags |= FASTNMS_FRAME_MALFORMED;
        dec->payload = FASTNMS_REC_ORB_BEATS - 1u;
        dec->payload_last = last;
        if (dec->payload_slot != SIZE_MAX && dec->orb_storage != NULL) {
            const struct fastnms_orb zero = {0};
            dec->payload_orb = zero;
        }
        return false;
    }
    return last;
}

/* Deliver the frame in progress and start the next one. */
static void deliver(struct fastnms_decoder *dec, struct fastnms_frame *frame, uint32_t flags)
{
    frame->index = dec->index;
    frame->flags = dec->flags | flags;
    frame->records = dec->records;
    frame->words = dec->words;
    frame->corners = dec->corners;
    frame->stored = dec->stored;
    frame->first_word = dec->first_word;
    frame->corner = dec->storage;
    frame->orb = dec->orb_storage;
    dec->index++;
    start_frame(dec);
}

int fastnms_decode(struct fastnms_decoder *dec, const uint64_t *words, size_t count,
                   size_t *consumed, struct fastnms_frame *frame)
{
    size_t i;

    if (dec == NULL || consumed == NULL || frame == NULL || (words == NULL && count != 0u))
        return FASTNMS_ERR_ARG;
    for (i = 0; i < count; i++) {
        if (take_record(dec, words[i])) {
            *consumed = i + 1u;
            deliver(dec, frame, 0u);
            return FASTNMS_FRAME;
        }
    }
    *consumed = count;
    return FASTNMS_OK;
}

int fastnms_decoder_flush(struct fastnms_decoder *dec, struct fastnms_frame *frame)
{
    if (dec == NULL || frame == NULL)
        return FASTNMS_ERR_ARG;
    if (dec->words == 0u)
        return FASTNMS_OK;
    deliver(dec, frame, FASTNMS_FRAME_INCOMPLETE);
    return FASTNMS_FRAME;
}

size_t fastnms_decoder_pending(const struct fastnms_decoder *dec)
{
    return dec == NULL ? 0u : dec->records;
}

int fastnms_decode_all(const uint64_t *words, size_t count, struct fastnms_corner *corners,
                       size_t corner_capacity, struct fastnms_frame *frames,
                       size_t frame_capacity, size_t *frame_count, size_t *corner_count)
{
    struct fastnms_decoder dec;
    struct fastnms_frame frame;
    size_t frames_found = 0, corners_found = 0, used = 0;
    int rc;

    if ((words == NULL && count != 0u) || (corners == NULL && corner_capacity != 0u) ||
        (frames == NULL && frame_capacity != 0u) || frame_count == NULL || corner_count == NULL)
        return FASTNMS_ERR_ARG;
    (void)fastnms_decoder_init(&dec, corners, corner_capacity);
    for (;;) {
        size_t consumed = 0;
        rc = fastnms_decode(&dec, words, count, &consumed, &frame);
        if (rc == FASTNMS_OK)
            rc = fastnms_decoder_flush(&dec, &frame);
        if (rc != FASTNMS_FRAME)
            break;
        words += consumed; /* consumed <= count: within the array or one past */
        count -= consumed;
        if (frames_found < frame_capacity)
            frames[frames_found] = frame;
        frames_found = saturating_increment(frames_found);
        corners_found += frame.corners <= SIZE_MAX - corners_found ? frame.corners
                                                                   : SIZE_MAX - corners_found;
        /* The next frame's corners follow this one's in `corners`. */
        used += frame.stored;
        dec.storage = corners == NULL ? NULL : corners + used;
        dec.capacity = corner_capacity - used;
    }
    *frame_count = frames_found;
    *corner_count = corners_found;
    if (rc != FASTNMS_OK)
        return rc;
    return frames_found > frame_capacity || corners_found > corner_capacity ? FASTNMS_ERR_NO_SPACE
                                                                            : FASTNMS_OK;
}

/* ---- the register helpers ---------------------------------------------------- */

static bool usable(const struct fastnms_regs_io *io)
{
    return io != NULL && io->read != NULL && io->write != NULL;
}

static uint32_t rd(const struct fastnms_regs_io *io, uint32_t offset)
{
    return io->read(io->ctx, offset);
}

static void wr(const struct fastnms_regs_io *io, uint32_t offset, uint32_t value)
{
    io->write(io->ctx, offset, value);
}

int fastnms_probe(const struct fastnms_regs_io *io, struct fastnms_info *info)
{
    uint32_t version, size, build, mode;
    uint32_t major, minor;

    if (!usable(io))
        return FASTNMS_ERR_ARG;
    if (FIELD(rd(io, FASTNMS_ID_OFFSET), ID_MAGIC) != FASTNMS_ID_MAGIC_RESET)
        return FASTNMS_ERR_ID;
    version = rd(io, FASTNMS_VERSION_OFFSET);
    major = FIELD(version, VERSION_MAJOR);
    minor = FIELD(version, VERSION_MINOR);
    /* Semantic versioning: a new major breaks the map, and so does a new minor
     * while the major is 0; a later minor only adds to it. */
    if (major != FASTNMS_VERSION_MAJOR_RESET ||
        (major == 0u ? minor != FASTNMS_VERSION_MINOR_RESET : minor < FASTNMS_VERSION_MINOR_RESET))
        return FASTNMS_ERR_VERSION;
    if (info != NULL) {
        size = rd(io, FASTNMS_MAX_SIZE_OFFSET);
        build = rd(io, FASTNMS_BUILD_OFFSET);
        mode = rd(io, FASTNMS_MODE_OFFSET);
        info->major = (uint8_t)major;
        info->minor = (uint8_t)minor;
        info->patch = (uint8_t)FIELD(version, VERSION_PATCH);
        info->max_width = (uint16_t)FIELD(size, MAX_SIZE_WIDTH);
        info->max_height = (uint16_t)FIELD(size, MAX_SIZE_HEIGHT);
        info->fifo_depth = (uint16_t)FIELD(build, BUILD_FIFO_DEPTH);
        info->score_video = FIELD(build, BUILD_SCORE_VIDEO) != 0u;
        info->score = (uint8_t)FIELD(mode, MODE_SCORE);
        info->nms = (uint8_t)FIELD(mode, MODE_NMS);
        info->ppc = (uint8_t)FIELD(mode, MODE_PPC);
        info->max_per_cell = (uint8_t)FIELD(build, BUILD_MAX_PER_CELL);
    }
    return FASTNMS_OK;
}

int fastnms_configure(const struct fastnms_regs_io *io, uint32_t width, uint32_t height,
                      uint32_t threshold)
{
    uint32_t size;

    if (!usable(io))
        return FASTNMS_ERR_ARG;
    size = rd(io, FASTNMS_MAX_SIZE_OFFSET);
    if (width < FASTNMS_MIN_SIZE || width > FIELD(size, MAX_SIZE_WIDTH) ||
        height < FASTNMS_MIN_SIZE || height > FIELD(size, MAX_SIZE_HEIGHT) ||
        threshold > FIELD(FASTNMS_THRESHOLD_VALUE_MASK, THRESHOLD_VALUE))
        return FASTNMS_ERR_RANGE;
    wr(io, FASTNMS_WIDTH_OFFSET, width << FASTNMS_WIDTH_VALUE_SHIFT);
    wr(io, FASTNMS_HEIGHT_OFFSET, height << FASTNMS_HEIGHT_VALUE_SHIFT);
    wr(io, FASTNMS_THRESHOLD_OFFSET, threshold << FASTNMS_THRESHOLD_VALUE_SHIFT);
    return FASTNMS_OK;
}

int fastnms_set_budget(const struct fastnms_regs_io *io, uint32_t cell, uint32_t per_cell)
{
    uint32_t build;

    if (!usable(io))
        return FASTNMS_ERR_ARG;
    build = rd(io, FASTNMS_BUILD_OFFSET);
    if (cell < 16u || cell > 256u || (cell & (cell - 1u)) != 0u ||
        per_cell > FIELD(build, BUILD_MAX_PER_CELL))
        return FASTNMS_ERR_RANGE;
    wr(io, FASTNMS_BUDGET_OFFSET,
       cell << FASTNMS_BUDGET_CELL_SHIFT | per_cell << FASTNMS_BUDGET_PER_CELL_SHIFT);
    return FASTNMS_OK;
}

int fastnms_set_min_area(const struct fastnms_regs_io *io, uint32_t min_area)
{
    if (!usable(io))
        return FASTNMS_ERR_ARG;
    if (min_area > FASTNMS_AREA_MAX)
        return FASTNMS_ERR_RANGE;
    wr(io, FASTNMS_MIN_AREA_OFFSET, min_area << FASTNMS_MIN_AREA_VALUE_SHIFT);
    return FASTNMS_OK;
}

/* CTRL with `bit` set or cleared, its other fields as read. */
static int ctrl_update(const struct fastnms_regs_io *io, uint32_t bit, bool on)
{
    const uint32_t fields =
        FASTNMS_CTRL_ENABLE_MASK | FASTNMS_CTRL_IRQ_ENABLE_MASK | FASTNMS_CTRL_LIVE_MASK;
    uint32_t value;

    if (!usable(io))
        return FASTNMS_ERR_ARG;
    value = rd(io, FASTNMS_CTRL_OFFSET) & fields;
    value = on ? value | bit : value & ~bit;
    wr(io, FASTNMS_CTRL_OFFSET, value);
    return FASTNMS_OK;
}

int fastnms_set_enable(const struct fastnms_regs_io *io, bool on)
{
    return ctrl_update(io, FASTNMS_CTRL_ENABLE_MASK, on);
}

int fastnms_set_irq_enable(const struct fastnms_regs_io *io, bool on)
{
    return ctrl_update(io, FASTNMS_CTRL_IRQ_ENABLE_MASK, on);
}

int fastnms_set_live(const struct fastnms_regs_io *io, bool on)
{
    return ctrl_update(io, FASTNMS_CTRL_LIVE_MASK, on);
}

int fastnms_soft_reset(const struct fastnms_regs_io *io, uint32_t max_polls)
{
    uint32_t i;

    if (!usable(io))
        return FASTNMS_ERR_ARG;
    if (max_polls == 0u)
        max_polls = FASTNMS_SOFT_RESET_POLLS;
    wr(io, FASTNMS_CMD_OFFSET,
       ((FASTNMS_CMD_KEY_UNLOCK << FASTNMS_CMD_KEY_SHIFT) & FASTNMS_CMD_KEY_MASK) |
           FASTNMS_CMD_SOFT_RESET_MASK);
    for (i = 0; i < max_polls; i++) {
        if ((rd(io, FASTNMS_CMD_OFFSET) & FASTNMS_CMD_SOFT_RESET_MASK) == 0u)
            return FASTNMS_OK;
    }
    return FASTNMS_ERR_TIMEOUT;
}

uint32_t fastnms_status(const struct fastnms_regs_io *io)
{
    return usable(io) ? rd(io, FASTNMS_STATUS_OFFSET) : 0u;
}

int fastnms_clear_status(const struct fastnms_regs_io *io, uint32_t mask)
{
    if (!usable(io))
        return FASTNMS_ERR_ARG;
    mask &= FASTNMS_STATUS_STICKY;
    if (mask != 0u)
        wr(io, FASTNMS_STATUS_OFFSET, mask);
    return FASTNMS_OK;
}

int fastnms_read_counters(const struct fastnms_regs_io *io, struct fastnms_counters *counters)
{
    if (!usable(io) || counters == NULL)
        return FASTNMS_ERR_ARG;
    counters->corner_count = rd(io, FASTNMS_CORNER_COUNT_OFFSET);
    counters->frame_count = rd(io, FASTNMS_FRAME_COUNT_OFFSET);
    counters->dropped = rd(io, FASTNMS_DROPPED_OFFSET);
    counters->input_stalls = rd(io, FASTNMS_INPUT_STALLS_OFFSET);
    return FASTNMS_OK;
}
