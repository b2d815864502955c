/* exact_sum.h - an exact accumulator of floating-point numbers (a long fixed-point integer, after Kulisch): every
 * finite double or float added to it is held without rounding, so the sum of any numbers in any order, split in any
 * way and the parts merged in any order, is the same integer, and rounding it once gives the same bits - the
 * correctly rounded sum. It compiles as C and as OpenCL C (integers only: 64-bit limbs; a float is taken apart from
 * its bits, never through double), the same bits on every device.
 *
 * Used for the sums a run over many devices must get right whatever the decomposition (docs/design.md "Sums that do
 * not depend on the decomposition"): the walls' forces (common/wall_forces.h), hence servo and until_force
 * decisions, the energies and series rows (host/physics/energy.c), the spheres' volume of dem_relative_density.
 *
 * Layout: EXACT_LIMBS 64-bit limbs, two's complement, limb 0 the lowest; bit k of the whole integer stands for
 * 2^(k - 1074) (2^-1074 is the smallest subnormal double). A finite double's bits lie between 2^-1074 and 2^1023
 * (bit 2097); 34 limbs hold 2176 bits: the sign and 77 bits of headroom, room for 2^77 terms of the largest
 * magnitude before the sum could overflow. Infinities and NaNs are flagged beside the limbs and give what IEEE
 * addition gives: a NaN, or +inf + -inf, makes the sum NaN; one kind of infinity makes it that infinity. A sum that is
 * exactly zero (no terms, only zeros, or terms that cancel) is +0, as a loop from s = 0 gives and math.fsum does; a
 * non-zero sum too small for the format rounds to a zero of its sign.
 *
 * Each work item keeps its own accumulator (private memory: 280 bytes) and accumulators are merged afterwards; the
 * functions take private pointers (OpenCL C 1.2), so two items never add into one accumulator. In OpenCL C the double
 * functions exist in a program built with DEM_REAL_SIZE 8, and dem_real.h (which enables cl_khr_fp64) must come
 * first.
 */
#ifndef DEM_EXACT_SUM_H
#define DEM_EXACT_SUM_H

#define EXACT_LIMBS 34
#define EXACT_BIAS 1074 /* bit k stands for 2^(k - EXACT_BIAS) */
/* doubles in OpenCL C only where the program has them (a run's fp64 build: dem_real.h enables cl_khr_fp64) */
#if !defined(__OPENCL_C_VERSION__) || (defined(DEM_REAL_SIZE) && DEM_REAL_SIZE == 8)
#define EXACT_HAS_DOUBLE 1
#else
#define EXACT_HAS_DOUBLE 0
#endif

#ifdef __OPENCL_C_VERSION__
typedef ulong exact_u64;
typedef long exact_i64;
#define EXACT_INLINE static inline __attribute__((always_inline))
#if EXACT_HAS_DOUBLE
#define exact_double_bits(x) as_ulong(x)
#endif
#define exact_float_bits(x) as_uint(x)
#define exact_clz(x) clz(x)
#else
#include <stdint.h>
#include <string.h>
typedef uint64_t exact_u64;
typedef int64_t exact_i64;
#define EXACT_INLINE static inline
static inline exact_u64 exact_double_bits(double x)
{
    exact_u64 b;
    memcpy(&b, &x, sizeof b);
    return b;
}
#define exact_clz(x) __builtin_clzll(x) /* x != 0 */
static inline unsigned exact_float_bits(float x)
{
    unsigned b;
    memcpy(&b, &x, sizeof b);
    return b;
}
#endif

typedef struct {
    exact_u64 limb[EXACT_LIMBS];
    unsigned special; /* EXACT_NAN, EXACT_PINF, EXACT_NINF: what the limbs cannot hold */
} exact_acc;
enum { EXACT_NAN = 1, EXACT_PINF = 2, EXACT_NINF = 4 };

EXACT_INLINE void exact_clear(exact_acc *a)
{
    for (int k = 0; k < EXACT_LIMBS; k++)
        a->limb[k] = 0;
    a->special = 0;
}

/* adds (neg = 0) or subtracts (neg = 1) the integer m (< 2^53) times 2^pos (bit position pos >= 0) */
EXACT_INLINE void exact_add_bits(exact_acc *a, exact_u64 m, int pos, int neg)
{
    int k = pos >> 6, s = pos & 63;
    exact_u64 lo = m << s, hi = s ? m >> (64 - s) : 0;
    if (!neg) {
        exact_u64 t = a->limb[k] + lo, c = t < lo;
        a->limb[k] = t;
        for (int j = k + 1; j < EXACT_LIMBS; j++) { /* the carry, and the high part, until nothing is left */
            exact_u64 add = (j == k + 1 ? hi : 0);
            exact_u64 u = a->limb[j] + add, c1 = u < add;
            exact_u64 v = u + c, c2 = v < c;
            a->limb[j] = v;
            c = c1 | c2;
            if (!c && j > k)
                break;
        }
    } else {
        exact_u64 t = a->limb[k], b = t < lo;
        a->limb[k] = t - lo;
        for (int j = k + 1; j < EXACT_LIMBS; j++) { /* the borrow, and the high part */
            exact_u64 sub = (j == k + 1 ? hi : 0);
            exact_u64 u = a->limb[j], b1 = u < sub;
            u -= sub;
            exact_u64 b2 = u < b;
            a->limb[j] = u - b;
            b = b1 | b2;
            if (!b && j > k)
                break;
        }
    }
}

#if EXACT_HAS_DOUBLE
/* x into the sum, exactly (infinities and NaNs are left out) */
EXACT_INLINE void exact_add_double(exact_acc *a, double x)
{
    exact_u64 b = exact_double_bits(x);
    int e = (int)((b >> 52) & 2047);
    exact_u64 m = b & (((exact_u64)1 << 52) - 1);
    if (e == 2047) { /* an infinity or a NaN: flagged */
        a->special |= m ? EXACT_NAN : (b >> 63) ? EXACT_NINF : EXACT_PINF;
        return;
    }
    if (e == 0 && m == 0)
        return;
    if (e) /* normal: the hidden bit; a subnormal keeps the exponent of the smallest normal */
        m |= (exact_u64)1 << 52;
    exact_add_bits(a, m, e ? e - 1 : 0, (int)(b >> 63));
}
#endif
EXACT_INLINE void exact_add_float(exact_acc *a, float x)
{
    unsigned b = exact_float_bits(x);
    int e = (int)((b >> 23) & 255);
    exact_u64 m = b & ((1u << 23) - 1);
    if (e == 255) {
        a->special |= m ? EXACT_NAN : (b >> 31) ? EXACT_NINF : EXACT_PINF;
        return;
    }
    if (e == 0 && m == 0)
        return;
    if (e)
        m |= (exact_u64)1 << 23;
    /* a float m 2^(e - 150) (subnormal: e = 1): bit position e - 150 + 1074 */
    exact_add_bits(a, m, (e ? e : 1) - 150 + EXACT_BIAS, (int)(b >> 31));
}

/* b added into a, exactly (limb by limb with the carry) */
EXACT_INLINE void exact_merge(exact_acc *a, const exact_acc *b)
{
    exact_u64 c = 0;
    for (int k = 0; k < EXACT_LIMBS; k++) {
        exact_u64 u = a->limb[k] + b->limb[k], c1 = u < b->limb[k];
        exact_u64 v = u + c, c2 = v < c;
        a->limb[k] = v;
        c = c1 | c2;
    }
    a->special |= b->special;
}

/* The sum rounded to nearest (ties to even) with p significant bits (53: double, 24: float) and its smallest
 * exponent emin (the value of the lowest bit of a subnormal: -1074, -149): *neg its sign, the result m 2^q with
 * m < 2^p (0 when the sum is 0); returns 1 when the sum overflows the format (an infinity), else 0 */
EXACT_INLINE int exact_round(const exact_acc *a, int p, int emin, int emax, int *neg, exact_u64 *m, int *q)
{
    exact_acc v = *a;
    *neg = (int)(v.limb[EXACT_LIMBS - 1] >> 63);
    if (*neg) { /* the magnitude: two's complement */
        exact_u64 c = 1;
        for (int k = 0; k < EXACT_LIMBS; k++) {
            exact_u64 u = ~v.limb[k] + c;
            c = c && u == 0;
            v.limb[k] = u;
        }
    }
    int top = -1; /* the highest set bit */
    for (int k = EXACT_LIMBS - 1; k >= 0 && top < 0; k--)
        if (v.limb[k])
            top = 64 * k + 63 - (int)exact_clz(v.limb[k]);
    *m = 0, *q = emin;
    if (top < 0)
        return 0;
    /* the lowest bit kept: p bits below and including top, but not below emin's bit */
    int low = top - (p - 1), lowest = emin + EXACT_BIAS;
    if (low < lowest)
        low = lowest;
    exact_u64 mm = 0;
    if (top >= low) { /* bits low..top (at most p <= 53 of them) from the limb of low and the next */
        int L = low >> 6, s = low & 63;
        exact_u64 w = v.limb[L] >> s;
        if (s && L + 1 < EXACT_LIMBS)
            w |= v.limb[L + 1] << (64 - s);
        mm = w & ((((exact_u64)1) << (top - low + 1)) - 1);
    }
    int g = low - 1; /* the guard bit's position; the sticky bits below it */
    int guard = g >= 0 ? (int)((v.limb[g >> 6] >> (g & 63)) & 1) : 0, sticky = 0;
    if (g > 0) {
        for (int k = 0; k < (g >> 6); k++) /* whole limbs below the guard's */
            sticky |= v.limb[k] != 0;
        sticky |= (g & 63) && (v.limb[g >> 6] & ((((exact_u64)1) << (g & 63)) - 1)) != 0;
    }
    if (guard && (sticky || (mm & 1)))
        mm++;
    int qq = low - EXACT_BIAS;
    if (mm >> p) /* rounded up to 2^p */
        mm >>= 1, qq++;
    *m = mm, *q = qq;
    return qq + p - 1 > emax;
}

/* An accumulator in global memory, as 2 EXACT_LIMBS + 1 unsigned words (each limb low word first, then the
 * flags): a buffer of unsigned is all the registry needs (no 64-bit element type), and a partial sum of one work item
 * is stored for another to merge (common/wall_forces.h). A zero accumulator is stored as its flags word alone,
 * marked EXACT_EMPTY, and merged as nothing: most blocks of a run touch no wall, and their 272 bytes of zero limbs
 * were written and read again at every sum. */
#define EXACT_WORDS (2 * EXACT_LIMBS + 1)
#define EXACT_EMPTY 8u /* in a stored flags word only: the limbs were not written (all zero) */
#ifdef __OPENCL_C_VERSION__
#define EXACT_GLOBAL __global
#else
#define EXACT_GLOBAL
#endif
EXACT_INLINE void exact_store(EXACT_GLOBAL unsigned *p, const exact_acc *a)
{
    exact_u64 any = a->special;
    for (int k = 0; k < EXACT_LIMBS; k++)
        any |= a->limb[k];
    if (!any) {
        p[2 * EXACT_LIMBS] = EXACT_EMPTY;
        return;
    }
    for (int k = 0; k < EXACT_LIMBS; k++) {
        p[2 * k] = (unsigned)a->limb[k];
        p[2 * k + 1] = (unsigned)(a->limb[k] >> 32);
    }
    p[2 * EXACT_LIMBS] = a->special;
}
/* the stored accumulator p added into a, exactly */
EXACT_INLINE void exact_merge_stored(exact_acc *a, const EXACT_GLOBAL unsigned *p)
{
    if (p[2 * EXACT_LIMBS] & EXACT_EMPTY)
        return;
    exact_acc b;
    for (int k = 0; k < EXACT_LIMBS; k++)
        b.limb[k] = (exact_u64)p[2 * k] | ((exact_u64)p[2 * k + 1] << 32);
    b.special = p[2 * EXACT_LIMBS];
    exact_merge(a, &b);
}
/* a set to the sum of the count stored accumulators at p, p + stride, ... (stride in words): one level of a tree of
 * sums (common/wall_forces.h's, and the host's reading of it) */
EXACT_INLINE void exact_sum_stored(exact_acc *a, const EXACT_GLOBAL unsigned *p, int count, long stride)
{
    exact_clear(a);
    for (int k = 0; k < count; k++)
        exact_merge_stored(a, p + k * stride);
}

/* The bits of the sum in a binary format of p significant bits and e exponent bits (double: 53, 11; float: 24, 8),
 * rounded once to nearest, ties to even: NaN for a NaN or both infinities among the terms, an infinity for one of them
 * or past the largest finite value */
EXACT_INLINE exact_u64 exact_bits(const exact_acc *a, int p, int e)
{
    int bias = (1 << (e - 1)) - 1, neg, q;
    exact_u64 m, b, inf = (((exact_u64)1 << e) - 1) << (p - 1), frac = ((exact_u64)1 << (p - 1)) - 1;
    int over = exact_round(a, p, 2 - bias - p, bias, &neg, &m, &q);
    unsigned sp = a->special;
    if (sp & (EXACT_PINF | EXACT_NINF)) /* an infinity among the terms: its sign */
        over = 1, neg = (sp & EXACT_NINF) != 0;
    if ((sp & EXACT_NAN) || ((sp & EXACT_PINF) && (sp & EXACT_NINF)))
        b = inf | ((exact_u64)1 << (p - 2)), neg = 0; /* a quiet NaN */
    else if (over)
        b = inf;
    else if (m >> (p - 1)) /* normal: m 2^q with 2^(p-1) <= m < 2^p, exponent field q + p - 1 + bias */
        b = ((exact_u64)(q + p - 1 + bias) << (p - 1)) | (m & frac);
    else /* subnormal (q the smallest exponent) or zero */
        b = m;
    return b | ((exact_u64)neg << (p + e - 1));
}

#if EXACT_HAS_DOUBLE
/* The sum as the nearest double */
EXACT_INLINE double exact_to_double(const exact_acc *a)
{
    exact_u64 b = exact_bits(a, 53, 11);
#ifdef __OPENCL_C_VERSION__
    return as_double(b);
#else
    double x;
    memcpy(&x, &b, sizeof x);
    return x;
#endif
}
#endif

/* The sum as the nearest float, rounded once from the exact sum (never through a double) */
EXACT_INLINE float exact_to_float(const exact_acc *a)
{
    unsigned b = (unsigned)exact_bits(a, 24, 8);
#ifdef __OPENCL_C_VERSION__
    return as_float(b);
#else
    float x;
    memcpy(&x, &b, sizeof x);
    return x;
#endif
}
#endif /* DEM_EXACT_SUM_H */
