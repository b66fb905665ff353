/* Test program of the record decoder (sw/tests/test_sw_records.py builds and runs it).
 *
 *   decode_records RECORDS [CHUNK [CAPACITY]]    stream: fastnms_decode, CHUNK words per
 *                                                call (default: all), room for CAPACITY
 *                                                corners (default: one per word)
 *   decode_records --all RECORDS FRAMES CORNERS  one shot: fastnms_decode_all with room for
 *                                                FRAMES frames and CORNERS corners
 *
 * RECORDS: 64-bit little-endian record words. Prints each frame as
 *   frame INDEX first FIRST_WORD records N words N corners N stored N flags NAME,NAME|-
 * followed by one "X Y SCORE" line per stored corner ("X Y SCORE ANGLE DESCRIPTOR", in
 * hexadecimal, in an ORB frame of the stream mode), with " area AREA" at its end when
 * the corner's AREA is not 0 (region NMS); the one-shot mode ends with
 *   result CODE frames N corners N
 * Exit status 0, or 1 on a usage or file error.
 */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "fastnms.h"

static void print_frame(const struct fastnms_frame *f)
{
    static const struct {
        uint32_t bit;
        const char *name;
    } names[] = {
        {FASTNMS_FRAME_EMPTY, "empty"},           {FASTNMS_FRAME_ABORTED, "aborted"},
        {FASTNMS_FRAME_OVERFLOW, "overflow"},     {FASTNMS_FRAME_INCOMPLETE, "incomplete"},
        {FASTNMS_FRAME_MALFORMED, "malformed"},   {FASTNMS_FRAME_TRUNCATED, "truncated"},
        {FASTNMS_FRAME_ORB, "orb"},
        {FASTNMS_FRAME_ERROR, "error"},
    };
    const char *sep = "";
    size_t i;

    printf("frame %lu first %llu records %lu words %lu corners %lu stored %lu flags ",
           (unsigned long)f->index, (unsigned long long)f->first_word, (unsigned long)f->records,
           (unsigned long)f->words, (unsigned long)f->corners, (unsigned long)f->stored);
    for (i = 0; i < sizeof names / sizeof names[0]; i++) {
        if (f->flags & names[i].bit) {
            printf("%s%s", sep, names[i].name);
            sep = ",";
        }
    }
    printf("%s\n", *sep ? "" : "-");
    for (i = 0; i < f->stored; i++) {
        printf("%u %u %u", f->corner[i].x, f->corner[i].y, f->corner[i].score);
        if ((f->flags & FASTNMS_FRAME_ORB) && f->orb != NULL) {
            size_t b;
            printf(" %08lx ", (unsigned long)f->orb[i].angle_bits);
            for (b = 0; b < sizeof f->orb[i].descriptor; b++)
                printf("%02x", f->orb[i].descriptor[b]);
        }
        if (f->corner[i].area != 0u)
            printf(" area %u", f->corner[i].area);
        printf("\n");
    }
}

static uint64_t *read_words(const char *path, size_t *count)
{
    FILE *file = fopen(path, "rb");
    unsigned char bytes[8];
    uint64_t *words = NULL;
    size_t n = 0, room = 0;

    if (file == NULL)
        return NULL;
    while (fread(bytes, 1, sizeof bytes, file) == sizeof bytes) {
        uint64_t word = 0;
        int b;
        if (n == room) {
            uint64_t *more;
            room = room ? 2 * room : 64;
            more = realloc(words, room * sizeof *words);
            if (more == NULL) {
                free(words);
                fclose(file);
                return NULL;
            }
            words = more;
        }
        for (b = 7; b >= 0; b--)
            word = word << 8 | bytes[b];
        words[n++] = word;
    }
    fclose(file);
    *count = n;
    return words != NULL ? words : malloc(1);
}

static int stream(const uint64_t *words, size_t count, size_t chunk, size_t capacity)
{
    struct fastnms_corner *storage = capacity ? malloc(capacity * sizeof *storage) : NULL;
    struct fastnms_orb *orb = capacity ? malloc(capacity * sizeof *orb) : NULL;
    struct fastnms_decoder dec;
    struct fastnms_frame frame;
    size_t at = 0;
    int rc;

    if (capacity && (storage == NULL || orb == NULL))
        return 1;
    if (fastnms_decoder_init(&dec, storage, capacity) != FASTNMS_OK ||
        fastnms_decoder_set_orb(&dec, orb) != FASTNMS_OK)
        return 1;
    /* Pieces of `chunk` words, as DMA buffers: a frame may span several. */
    while (at < count) {
        size_t piece = count - at < chunk ? count - at : chunk;
        const uint64_t *p = words + at;
        at += piece;
        while (piece > 0) {
            size_t used = 0;
            rc = fastnms_decode(&dec, p, piece, &used, &frame);
            if (rc < 0) {
                printf("error %d %s\n", rc, fastnms_strerror(rc));
                free(storage);
                free(orb);
                return 1;
            }
            p += used;
            piece -= used;
            if (rc == FASTNMS_FRAME)
                print_frame(&frame);
        }
    }
    if (fastnms_decoder_flush(&dec, &frame) == FASTNMS_FRAME)
        print_frame(&frame);
    free(storage);
    free(orb);
    return 0;
}

static int one_shot(const uint64_t *words, size_t count, size_t max_frames, size_t max_corners)
{
    struct fastnms_corner *corners = malloc(max_corners ? max_corners * sizeof *corners : 1);
    struct fastnms_frame *frames = malloc(max_frames ? max_frames * sizeof *frames : 1);
    size_t n_frames = 0, n_corners = 0, i;
    int rc;

    if (corners == NULL || frames == NULL)
        return 1;
    rc = fastnms_decode_all(words, count, corners, max_corners, frames, max_frames, &n_frames,
                            &n_corners);
    for (i = 0; i < n_frames && i < max_frames; i++)
        print_frame(&frames[i]);
    printf("result %d frames %lu corners %lu\n", rc, (unsigned long)n_frames,
           (unsigned long)n_corners);
    free(corners);
    free(frames);
    return 0;
}

int main(int argc, char **argv)
{
    const bool all = argc > 1 && strcmp(argv[1], "--all") == 0;
    const int first = all ? 2 : 1;
    uint64_t *words;
    size_t count = 0;
    int rc;

    if (argc < first + 1 || (all && argc != 5) || (!all && argc > 4)) {
        fprintf(stderr, "usage: decode_records RECORDS [CHUNK [CAPACITY]]\n"
                        "       decode_records --all RECORDS FRAMES CORNERS\n");
        return 1;
    }
    words = read_words(argv[first], &count);
    if (words == NULL) {
        fprintf(stderr, "decode_records: cannot read %s\n", argv[first]);
        return 1;
    }
    if (all) {
        rc = one_shot(words, count, strtoul(argv[3], NULL, 10), strtoul(argv[4], NULL, 10));
    } else {
        size_t chunk = argc > 2 ? strtoul(argv[2], NULL, 10) : count;
        size_t capacity = argc > 3 ? strtoul(argv[3], NULL, 10) : count;
        rc = stream(words, count, chunk ? chunk : 1, capacity);
    }
    free(words);
    return rc;
}
