/* LCM's encodings are big-endian: the fields of the log format
 * (lcm_log.c) and of hand-decoded messages (image_t in src/sources,
 * params_t in src/daemon), read and written here once. Internal to rtedge. */
#ifndef RTEDGE_LCM_WIRE_H
#define RTEDGE_LCM_WIRE_H

#include <stdint.h>

static inline uint32_t rte_lcm_get_u32(const uint8_t *p)
{
    return (uint32_t)p[0] << 24 | (uint32_t)p[1] << 16 | (uint32_t)p[2] << 8 | p[3];
}

static inline uint64_t rte_lcm_get_u64(const uint8_t *p)
{
    return (uint64_t)rte_lcm_get_u32(p) << 32 | rte_lcm_get_u32(p + 4);
}

static inline void rte_lcm_put_u32(uint8_t *p, uint32_t v)
{
    p[0] = (uint8_t)(v >> 24);
    p[1] = (uint8_t)(v >> 16);
    p[2] = (uint8_t)(v >> 8);
    p[3] = (uint8_t)v;
}

static inline void rte_lcm_put_u64(uint8_t *p, uint64_t v)
{
    rte_lcm_put_u32(p, (uint32_t)(v >> 32));
    rte_lcm_put_u32(p + 4, (uint32_t)v);
}

#endif
