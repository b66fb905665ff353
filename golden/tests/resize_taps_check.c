/* The RTL resizer's tap algorithm (rtl/resize: fastnms_resize_scale, fastnms_resize_taps)
   against OpenCV's INTER_LINEAR_EXACT steps in the CPU's IEEE doubles, for every shrink
   pair 1 <= dst <= src <= MAX_SRC of one axis:
   - the scale: inv = RN(dst / src), scale = RN(1 / inv) by two restoring divisions on
     integers, giving m = scale * 2**52 (checked for every pair up to SETUP_MAX);
   - the taps: P = m * (2i + 1) accumulated, rounded to 53 significant bits at its
     leading one, then o = floor(t - 0.5) and c1 = RN(frac * 256) from bits 64..44 and a
     sticky bit (checked for every pair up to MAX_SRC), against o and c0 of
     OpenCV's getCoeffs: f = scale * (i + 0.5) - 0.5 in doubles.
   Usage: resize_taps_check MAX_SRC SETUP_MAX; prints the counts, exit 1 on a difference.
   Build without -ffast-math and without FMA contraction (-ffp-contract=off). */
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>

typedef unsigned __int128 u128;

static int bit_length(u128 v) {
    int n = 0;
    while (v) {
        n++;
        v >>= 1;
    }
    return n;
}

/* RN to even of (sig: 53 bits taken, rb: the next bit, sticky), carry into bit 53 kept. */
static uint64_t round_even(uint64_t sig, int rb, int sticky) {
    return (rb && (sticky || (sig & 1))) ? sig + 1 : sig;
}

/* m = scale * 2**52 as fastnms_resize_scale computes it. */
static uint64_t scale_m(uint64_t src, uint64_t dst) {
    /* Phase 1: dst / src, quotient bits after the point; the first one at step j. */
    uint64_t rem = dst, sig = 0;
    int step = 0, got = 0, first = 0, rb = 0;
    while (got < 54) {
        step++;
        rem <<= 1;
        int q = rem >= src;
        if (q) rem -= src;
        if (!got && !q) continue;
        if (!got) first = step;
        if (got < 53) sig = (sig << 1) | (uint64_t)q;
        else rb = q;
        got++;
    }
    sig = round_even(sig, rb, rem != 0);
    uint64_t mi = sig;
    int j_plus1 = first + 1;
    if (sig >> 53) {
        mi = 1ull << 52;
        j_plus1 = first;
    }
    /* Phase 2: 2**(104 + j) / mi from 2**51 doubled at each step. */
    u128 r = (u128)1 << 51;
    sig = 0;
    got = 0;
    step = 0;
    first = 0;
    rb = 0;
    while (got < 54) {
        step++;
        r <<= 1;
        int q = r >= mi;
        if (q) r -= mi;
        if (!got && !q) continue;
        if (!got) first = step;
        if (got < 53) sig = (sig << 1) | (uint64_t)q;
        else rb = q;
        got++;
    }
    sig = round_even(sig, rb, r != 0);
    return sig << (j_plus1 - first);
}

int main(int argc, char **argv) {
    uint64_t max_src = argc > 1 ? strtoull(argv[1], 0, 10) : 400;
    uint64_t setup_max = argc > 2 ? strtoull(argv[2], 0, 10) : max_src;
    uint64_t top = max_src > setup_max ? max_src : setup_max;
    uint64_t pairs = 0, setup_bad = 0, taps = 0, taps_bad = 0;
    for (uint64_t src = 1; src <= top; src++)
        for (uint64_t dst = 1; dst <= src; dst++) {
            volatile double inv = (double)dst / (double)src;
            volatile double scale = 1.0 / inv;
            uint64_t m = scale_m(src, dst);
            pairs++;
            if (ldexp((double)m, -52) != scale || (double)m != ldexp(scale, 52)) {
                if (setup_bad++ < 5) fprintf(stderr, "scale %llu -> %llu\n",
                                             (unsigned long long)src, (unsigned long long)dst);
                continue;
            }
            if (src > max_src) continue;
            u128 p = m, twice = (u128)m << 1;
            for (uint64_t i = 0; i < dst; i++, p += twice) {
                int k = bit_length(p) - 53;
                u128 t = p;
                if (k > 0) {
                    u128 low = p & (((u128)1 << k) - 1), half = (u128)1 << (k - 1);
                    t = p - low;
                    if (low > half || (low == half && ((p >> k) & 1))) t += (u128)1 << k;
                }
                uint64_t g = (uint64_t)(t >> 44) - 256; /* f = t - 0.5 */
                int sticky = (t & (((u128)1 << 44) - 1)) != 0;
                long o = (long)(g >> 9), frac = (long)(g & 511);
                long c1 = (frac >> 1) + ((frac & 1) & (sticky | ((frac >> 1) & 1)));
                long c0 = (o >= (long)src - 1 || src == 1) ? 256 : 256 - c1;
                if (o >= (long)src - 1 || src == 1) o = (long)src - 1;
                /* OpenCV's getCoeffs in doubles */
                volatile double f = scale * ((double)i + 0.5) - 0.5;
                long od = (long)floor(f), c0d;
                if (od < 0 || src == 1) {
                    od = 0;
                    c0d = 256;
                } else if (od >= (long)src - 1) {
                    od = (long)src - 1;
                    c0d = 256;
                } else {
                    volatile double fr = f - (double)od;
                    c0d = 256 - lrint(fr * 256.0);
                }
                taps++;
                if (o != od || c0 != c0d) {
                    if (taps_bad++ < 5) fprintf(stderr, "tap %llu -> %llu, i %llu\n",
                                                (unsigned long long)src, (unsigned long long)dst,
                                                (unsigned long long)i);
                }
            }
        }
    printf("pairs %llu scale_differ %llu taps %llu taps_differ %llu\n",
           (unsigned long long)pairs, (unsigned long long)setup_bad,
           (unsigned long long)taps, (unsigned long long)taps_bad);
    return setup_bad || taps_bad;
}
