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

rte_f64 rte_f64_from_u64(uint64_t v);
rte_f64 rte_f64_add(rte_f64 a, rte_f64 b);
rte_f64 rte_f64_sub(rte_f64 a, rte_f64 b);
rte_f64 rte_f64_mul(rte_f64 a, rte_f64 b);
rte_f64 rte_f64_div(rte_f64 a, rte_f64 b);
bool rte_f64_lt(rte_f64 a, rte_f64 b);

#endif
