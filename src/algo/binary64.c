/* Integer emulation of the binary64 operations Otsu's method needs; see
 * binary64.h. Working significands carry the leading bit at bit 62 and ten
 * guard bits below the 53 that are kept, the lowest one "jammed" (sticky)
 * with every bit shifted out, which is enough for correct rounding. */
#include "binary64.h"

#define SIGN_BIT UINT64_C(0x8000000000000000)
#define FRAC_MASK UINT64_C(0x000FFFFFFFFFFFFF)
#define HIDDEN_BIT UINT64_C(0x0010000000000000)

/* x >> n with every bit shifted out OR-ed into bit 0. */
static uint64_t shift_right_jam(uint64_t x, int32_t n)
{
    if (n <= 0)
        return x;
    if (n >= 64)
        return x != 0;
    return (x >> n) | ((x << (64 - n)) != 0);
}

/* Index of the highest set bit of x != 0 (binary search, no builtins). */
static int32_t top_bit(uint64_t x)
{
    int32_t n = 0;
    for (int32_t step = 32; step > 0; step >>= 1)
        if (x >> (n + step))
            n += step;
    return n;
}

/* Value sig * 2^(e - 62), sig in [2^62, 2^63) (or 0), rounded to binary64. */
static rte_f64 round_pack(uint64_t sign, int32_t e, uint64_t sig)
{
    if (sig == 0)
        return sign;
    int32_t biased = e + 1023;
    if (biased <= 0) {
        /* Subnormal: rescale to units of 2^-1084, i.e. mantissa units of 2^-1074. */
        sig = shift_right_jam(sig, 1 - biased);
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
    return sign | ((uint64_t)biased << 52) | (m & FRAC_MASK);
}

/* Splits a finite non-zero value into sig * 2^(e - 52), sig in [2^52, 2^53). */
static int32_t unpack(rte_f64 a, uint64_t *sig)
{
    int32_t biased = (int32_t)((a >> 52) & 0x7FF);
    uint64_t frac = a & FRAC_MASK;
    if (biased == 0) {
        int32_t shift = 52 - top_bit(frac);
        *sig = frac << shift;
        return -1022 - shift;
    }
    *sig = frac | HIDDEN_BIT;
    return biased - 1023;
}

static bool is_zero(rte_f64 a) { return (a & ~SIGN_BIT) == 0; }

rte_f64 rte_f64_from_u64(uint64_t v)
{
    if (v == 0)
        return 0;
    int32_t lead = top_bit(v);
    /* Bring the leading bit to bit 62, keeping what falls off as sticky. */
    uint64_t sig = lead > 62 ? shift_right_jam(v, lead - 62) : v << (62 - lead);
    return round_pack(0, lead, sig);
}

rte_f64 rte_f64_add(rte_f64 a, rte_f64 b)
{
    if (is_zero(a))
        return is_zero(b) ? (a & b) : b; /* -0 + -0 = -0, otherwise +0 */
    if (is_zero(b))
        return a;
    uint64_t sa, sb;
    int32_t ea = unpack(a, &sa), eb = unpack(b, &sb);
    uint64_t sign_a = a & SIGN_BIT, sign_b = b & SIGN_BIT;
    sa <<= 10;
    sb <<= 10;
    /* Make |a| >= |b|. */
    if (eb > ea || (eb == ea && sb > sa)) {
        uint64_t t = sa; sa = sb; sb = t;
        int32_t te = ea; ea = eb; eb = te;
        t = sign_a; sign_a = sign_b; sign_b = t;
    }
    sb = shift_right_jam(sb, ea - eb);
    if (sign_a == sign_b) {
        uint64_t sum = sa + sb; /* < 2^64 */
        if (sum >> 63) {
            sum = shift_right_jam(sum, 1);
            ea++;
        }
        return round_pack(sign_a, ea, sum);
    }
    uint64_t diff = sa - sb;
    if (diff == 0)
        return 0; /* x - x = +0 under round-to-nearest */
    int32_t shift = 62 - top_bit(diff);
    return round_pack(sign_a, ea - shift, diff << shift);
}

rte_f64 rte_f64_sub(rte_f64 a, rte_f64 b) { return rte_f64_add(a, b ^ SIGN_BIT); }

rte_f64 rte_f64_mul(rte_f64 a, rte_f64 b)
{
    uint64_t sign = (a ^ b) & SIGN_BIT;
    if (is_zero(a) || is_zero(b))
        return sign;
    uint64_t ma, mb;
    int32_t e = unpack(a, &ma) + unpack(b, &mb);
    /* 106-bit product from 32-bit halves. */
    uint64_t a0 = ma & 0xFFFFFFFF, a1 = ma >> 32, b0 = mb & 0xFFFFFFFF, b1 = mb >> 32;
    uint64_t p00 = a0 * b0, p01 = a0 * b1, p10 = a1 * b0, p11 = a1 * b1;
    uint64_t mid = (p00 >> 32) + (p01 & 0xFFFFFFFF) + (p10 & 0xFFFFFFFF);
    uint64_t lo = (p00 & 0xFFFFFFFF) | (mid << 32);
    uint64_t hi = p11 + (p01 >> 32) + (p10 >> 32) + (mid >> 32);
    /* The product is in [2^104, 2^106): hi holds bits 64..105. */
    int32_t shift = (hi >> 41) ? 43 : 42; /* brings the leading bit to 62 */
    if (shift == 43)
        e++;
    uint64_t sig = (hi << (64 - shift)) | (lo >> shift);
    sig |= (lo << (64 - shift)) != 0;
    return round_pack(sign, e, sig);
}

rte_f64 rte_f64_div(rte_f64 a, rte_f64 b)
{
    uint64_t sign = (a ^ b) & SIGN_BIT;
    if (is_zero(a))
        return sign;
    if (is_zero(b))
        return sign | UINT64_C(0x7FF0000000000000);
    uint64_t ma, mb;
    int32_t e = unpack(a, &ma) - unpack(b, &mb);
    if (ma < mb) {
        ma <<= 1;
        e--;
    }
    /* 63 quotient bits of ma / mb in [1, 2), 8 then 9 bits per step:
     * r < mb < 2^54, so r << 9 stays below 2^63. */
    uint64_t r = ma << 8;
    uint64_t q = r / mb;
    r -= q * mb;
    for (int32_t i = 0; i < 6; i++) {
        r <<= 9;
        uint64_t digit = r / mb;
        r -= digit * mb;
        q = (q << 9) | digit;
    }
    q |= r != 0;
    return round_pack(sign, e, q);
}

/* Orders finite values (both zeros equal). */
static int64_t order_key(rte_f64 a)
{
    int64_t magnitude = (int64_t)(a & ~SIGN_BIT);
    return (a & SIGN_BIT) ? -magnitude : magnitude;
}

bool rte_f64_lt(rte_f64 a, rte_f64 b) { return order_key(a) < order_key(b); }
