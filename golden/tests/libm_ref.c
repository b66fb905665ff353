/* The C library's reference for golden/tests/test_trig.py: (float)cos((double)x) and
 * (float)sin((double)x) for float32 x given by bit pattern, as OpenCV's ORB computes them.
 * Built with -fno-builtin-sin -fno-builtin-cos so the compiler calls cos and sin themselves
 * rather than fusing them into sincos. */
#include <math.h>
#include <stdint.h>

typedef union {
    uint32_t u;
    float f;
} bits32;

static void one(uint32_t x, uint32_t *c, uint32_t *s) {
    bits32 in = {.u = x}, out_c, out_s;
    out_c.f = (float)cos((double)in.f);
    out_s.f = (float)sin((double)in.f);
    *c = out_c.u;
    *s = out_s.u;
}

/* The n consecutive bit patterns first, first + 1, ... */
void ref_range(uint32_t first, uint32_t n, uint32_t *cos_out, uint32_t *sin_out) {
    for (uint32_t i = 0; i < n; i++) one(first + i, &cos_out[i], &sin_out[i]);
}

/* The n bit patterns x[0 .. n-1]. */
void ref_list(const uint32_t *x, uint32_t n, uint32_t *cos_out, uint32_t *sin_out) {
    for (uint32_t i = 0; i < n; i++) one(x[i], &cos_out[i], &sin_out[i]);
}
