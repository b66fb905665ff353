/* fastnms on Linux through UIO: a sketch of a user-space driver (compiled by the tests,
 * never run here).
 *
 *   uio_example /dev/uioN [RECORDS_DEVICE [BYTES]]
 *
 * /dev/uioN: the core's AXI4-Lite registers (a "generic-uio" device tree node with the
 * core's address range and its interrupt). Sets a 640x480 frame at t = 20, enables
 * the interrupt, and waits for 10 frames, printing the counters of each. With
 * RECORDS_DEVICE (e.g. a u-dma-buf device, /dev/udmabuf0, the buffer an AXI DMA
 * writes m_axis_corners into; programming the DMA is not shown), the records found
 * there are decoded after each frame.
 */
#define _POSIX_C_SOURCE 200809L

#include <fcntl.h>
#include <stdio.h>
#include <stdlib.h>
#include <sys/mman.h>
#include <unistd.h>

#include "fastnms.h"

#define REGS_BYTES 4096u
#define MAX_CORNERS 65536u

static uint32_t mmio_read(void *ctx, uint32_t offset)
{
    return *(volatile uint32_t *)((volatile uint8_t *)ctx + offset);
}

static void mmio_write(void *ctx, uint32_t offset, uint32_t value)
{
    *(volatile uint32_t *)((volatile uint8_t *)ctx + offset) = value;
}

/* Block until the next interrupt (UIO: write 1 to unmask, read the event count). */
static int wait_interrupt(int fd)
{
    uint32_t unmask = 1, events;
    if (write(fd, &unmask, sizeof unmask) != (ssize_t)sizeof unmask)
        return -1;
    return read(fd, &events, sizeof events) == (ssize_t)sizeof events ? 0 : -1;
}

static void decode_buffer(const uint64_t *words, size_t count, struct fastnms_corner *storage)
{
    struct fastnms_decoder dec;
    struct fastnms_frame frame;
    size_t used, i;

    fastnms_decoder_init(&dec, storage, MAX_CORNERS);
    while (count > 0 && fastnms_decode(&dec, words, count, &used, &frame) == FASTNMS_FRAME) {
        words += used;
        count -= used;
        printf("  frame %u: %zu corners%s%s%s\n", (unsigned)frame.index, frame.corners,
               frame.flags & FASTNMS_FRAME_ABORTED ? ", aborted" : "",
               frame.flags & FASTNMS_FRAME_OVERFLOW ? ", records dropped" : "",
               frame.flags & FASTNMS_FRAME_TRUNCATED ? ", truncated" : "");
        for (i = 0; i < frame.stored && i < 5u; i++)
            printf("    (%u, %u) score %u\n", frame.corner[i].x, frame.corner[i].y,
                   frame.corner[i].score);
    }
}

int main(int argc, char **argv)
{
    struct fastnms_regs_io io;
    struct fastnms_info info;
    struct fastnms_counters counters;
    struct fastnms_corner *storage = NULL;
    const uint64_t *records = NULL;
    size_t record_bytes = 0;
    void *regs;
    int fd, rc, frame;

    if (argc < 2) {
        fprintf(stderr, "usage: uio_example /dev/uioN [RECORDS_DEVICE [BYTES]]\n");
        return 2;
    }
    fd = open(argv[1], O_RDWR | O_SYNC);
    if (fd < 0) {
        perror(argv[1]);
        return 1;
    }
    regs = mmap(NULL, REGS_BYTES, PROT_READ | PROT_WRITE, MAP_SHARED, fd, 0);
    if (regs == MAP_FAILED) {
        perror("mmap");
        return 1;
    }
    if (argc > 2) {
        int rfd = open(argv[2], O_RDONLY | O_SYNC);
        void *map;
        record_bytes = argc > 3 ? strtoul(argv[3], NULL, 0) : 1u << 20;
        map = rfd < 0 ? MAP_FAILED : mmap(NULL, record_bytes, PROT_READ, MAP_SHARED, rfd, 0);
        storage = malloc(MAX_CORNERS * sizeof *storage);
        if (map == MAP_FAILED || storage == NULL) {
            perror(argv[2]);
            return 1;
        }
        records = map;
    }
    io.read = mmio_read;
    io.write = mmio_write;
    io.ctx = regs;

    rc = fastnms_probe(&io, &info);
    if (rc != FASTNMS_OK) {
        fprintf(stderr, "fastnms: %s\n", fastnms_strerror(rc));
        return 1;
    }
    printf("fastnms %u.%u.%u, up to %ux%u, score %u, nms %u, FIFO %u records\n", info.major,
           info.minor, info.patch, info.max_width, info.max_height, info.score, info.nms,
           info.fifo_depth);
    rc = fastnms_configure(&io, 640, 480, 20);
    if (rc == FASTNMS_OK)
        rc = fastnms_set_live(&io, false);
    if (rc == FASTNMS_OK)
        rc = fastnms_clear_status(&io, FASTNMS_STATUS_STICKY);
    if (rc == FASTNMS_OK)
        rc = fastnms_set_irq_enable(&io, true);
    if (rc != FASTNMS_OK) {
        fprintf(stderr, "fastnms: %s\n", fastnms_strerror(rc));
        return 1;
    }
    for (frame = 0; frame < 10; frame++) {
        uint32_t status;
        if (wait_interrupt(fd) != 0) {
            perror("interrupt");
            return 1;
        }
        status = fastnms_status(&io);
        fastnms_read_counters(&io, &counters);
        fastnms_clear_status(&io, FASTNMS_STATUS_FRAME_DONE_MASK);
        printf("frame %u: %u corners, %u dropped, %u input stalls, status 0x%02x\n",
               (unsigned)counters.frame_count, (unsigned)counters.corner_count,
               (unsigned)counters.dropped, (unsigned)counters.input_stalls, (unsigned)status);
        if (records != NULL)
            decode_buffer(records, record_bytes / sizeof *records, storage);
    }
    fastnms_set_irq_enable(&io, false);
    return 0;
}
