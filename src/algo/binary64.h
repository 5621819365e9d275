/* IEEE 754 binary64 arithmetic in integer registers (internal).
 *
 * Otsu's threshold in OpenCV is decided by double-precision rounding (its
 * near-ties are broken by the last bit), and per-frame code in rtedge may
 * not touch the FPU. These few operations reproduce IEEE round-to-nearest-
 * even results bit for bit on finite values, subnormals included; there is
 * no NaN or infinity handling beyond overflow to infinity, which the
 * callers never reach. A value is its raw bit pattern. */
#ifndef RTEDGE_SRC_ALGO_BINARY64_H
#define RTEDGE_SRC_ALGO_BINARY64_H

#include <stdbool.h>
#include <stdint.h>

typedef uint64_t rte_f64;

#define RTE_F64_ONE UINT64_C(0x3FF0000000000000)

/* Defined here, inline: Otsu's search makes thousands of these operations
 * per frame. Working significands carry the leading bit at bit 62 and ten
 * guard bits below the 53 that are kept, the lowest one "jammed" (sticky)
 * with every bit shifted out, which is enough for correct rounding. */
#define F64_SIGN_BIT UINT64_C(0x8000000000000000)
#define F64_FRAC_MASK UINT64_C(0x000FFFFFFFFFFFFF)
#define F64_HIDDEN_BIT UINT64_C(0x0010000000000000)

/* 128-bit unsigned integers (GCC and Clang): one widening multiply, one
 * 128-by-64-bit division. */
__extension__ typedef unsigned __int128 f64_u128;

/* x >> n with every bit shifted out OR-ed into bit 0. */
static inline uint64_t f64_shift_right_jam(uint64_t x, int32_t n)
{
    if (n <= 0)
        return x;
    if (n >= 64)
        return x != 0;
    return (x >> n) | ((x << (64 - n)) != 0);
}

/* Index of the highest set bit of x != 0 (one integer instruction: lzcnt
 * or bsr on x86-64, clz on aarch64). */
static inline int32_t f64_top_bit(uint64_t x) { return 63 - __builtin_clzll(x); }

/* Value sig * 2^(e - 62), sig in [2^62, 2^63) (or 0), rounded to binary64. */
static inline rte_f64 f64_round_pack(uint64_t sign, int32_t e, uint64_t sig)
{
    if (sig == 0)
        return sign;
    int32_t biased = e + 1023;
    if (biased <= 0) {
        /* Subnormal: rescale to units of 2^-1084, i.e. mantissa units of 2^-1074. */
        sig = f64_shift_right_jam(sig, 1 - biased);
        biased = 0;
    }
    uint64_t round_bits = sig & 0x3FF;
    uint64_t m = sig >> 10;
    if (round_bits > 0x200 || (round_bits == 0x200 && (m & 1)))
        m++;
    if (biased == 0)
        return sign | m; /* m == 2^52 lands on the smallest normal exactly */
    if (m >> 53) {
        m >>= 1;
        biased++;
    }
    if (biased >= 2047)
        return sign | UINT64_C(0x7FF0000000000000);
    return sign | ((uint64_t)biased << 52) | (m & F64_FRAC_MASK);
}

/* Splits a finite non-zero value into sig * 2^(e - 52), sig in [2^52, 2^53). */
static inline int32_t f64_unpack(rte_f64 a, uint64_t *sig)
{
    int32_t biased = (int32_t)((a >> 52) & 0x7FF);
    uint64_t frac = a & F64_FRAC_MASK;
    if (biased == 0) {
        int32_t shift = 52 - f64_top_bit(frac);
        *sig = frac << shift;
        return -1022 - shift;
    }
    *sig = frac | F64_HIDDEN_BIT;
    return biased - 1023;
}

static inline bool f64_is_zero(rte_f64 a) { return (a & ~F64_SIGN_BIT) == 0; }

static inline rte_f64 rte_f64_from_u64(uint64_t v)
{
    if (v == 0)
        return 0;
    int32_t lead = f64_top_bit(v);
    /* Bring the leading bit to bit 62, keeping what falls off as sticky. */
    uint64_t sig = lead > 62 ? f64_shift_right_jam(v, lead - 62) : v << (62 - lead);
    return f64_round_pack(0, lead, sig);
}

static inline rte_f64 rte_f64_add(rte_f64 a, rte_f64 b)
{
    if (f64_is_zero(a))
        return f64_is_zero(b) ? (a & b) : b; /* -0 + -0 = -0, otherwise +0 */
    if (f64_is_zero(b))
        return a;
    uint64_t sa, sb;
    int32_t ea = f64_unpack(a, &sa), eb = f64_unpack(b, &sb);
    uint64_t sign_a = a & F64_SIGN_BIT, sign_b = b & F64_SIGN_BIT;
    sa <<= 10;
    sb <<= 10;
    /* Make |a| >= |b|. */
    if (eb > ea || (eb == ea && sb > sa)) {
        uint64_t t = sa;
        sa = sb;
        sb = t;
        int32_t te = ea;
        ea = eb;
        eb = te;
        t = sign_a;
        sign_a = sign_b;
        sign_b = t;
    }
    sb = f64_shift_right_jam(sb, ea - eb);
    if (sign_a == sign_b) {
        uint64_t sum = sa + sb; /* < 2^64 */
        if (sum >> 63) {
            sum = f64_shift_right_jam(sum, 1);
            ea++;
        }
        return f64_round_pack(sign_a, ea, sum);
    }
    uint64_t diff = sa - sb;
    if (diff == 0)
        return 0; /* x - x = +0 under round-to-nearest */
    int32_t shift = 62 - f64_top_bit(diff);
    return f64_round_pack(sign_a, ea - shift, diff << shift);
}

static inline rte_f64 rte_f64_sub(rte_f64 a, rte_f64 b) { return rte_f64_add(a, b ^ F64_SIGN_BIT); }

static inline rte_f64 rte_f64_mul(rte_f64 a, rte_f64 b)
{
    uint64_t sign = (a ^ b) & F64_SIGN_BIT;
    if (f64_is_zero(a) || f64_is_zero(b))
        return sign;
    uint64_t ma, mb;
    int32_t e = f64_unpack(a, &ma) + f64_unpack(b, &mb);
    /* 106-bit product (one widening multiply) */
    const f64_u128 p = (f64_u128)ma * mb;
    const uint64_t lo = (uint64_t)p, hi = (uint64_t)(p >> 64);
    /* The product is in [2^104, 2^106): hi holds bits 64..105. */
    int32_t shift = (hi >> 41) ? 43 : 42; /* brings the leading bit to 62 */
    if (shift == 43)
        e++;
    uint64_t sig = (hi << (64 - shift)) | (lo >> shift);
    sig |= (lo << (64 - shift)) != 0;
    return f64_round_pack(sign, e, sig);
}

static inline rte_f64 rte_f64_div(rte_f64 a, rte_f64 b)
{
    uint64_t sign = (a ^ b) & F64_SIGN_BIT;
    if (f64_is_zero(a))
        return sign;
    if (f64_is_zero(b))
        return sign | UINT64_C(0x7FF0000000000000);
    uint64_t ma, mb;
    int32_t e = f64_unpack(a, &ma) - f64_unpack(b, &mb);
    if (ma < mb) {
        ma <<= 1;
        e--;
    }
    /* 63 quotient bits of ma / mb in [1, 2): ma 2^62 / mb in [2^62, 2^63),
     * the remainder's bits jammed into the lowest one. The numerator's high
     * word (ma >> 2) is below mb, so this is one 128-by-64-bit division. */
    const f64_u128 num = (f64_u128)ma << 62;
    uint64_t q = (uint64_t)(num / mb);
    q |= (uint64_t)num != q * mb; /* num - q mb < mb < 2^64: its low word is the remainder */
    return f64_round_pack(sign, e, q);
}

/* Orders finite values (both zeros equal). */
static inline int64_t f64_order_key(rte_f64 a)
{
    int64_t magnitude = (int64_t)(a & ~F64_SIGN_BIT);
    return (a & F64_SIGN_BIT) ? -magnitude : magnitude;
}

static inline bool rte_f64_lt(rte_f64 a, rte_f64 b) { return f64_order_key(a) < f64_order_key(b); }

#endif
