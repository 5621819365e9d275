/* CPU feature probe: see include/rtedge/cpu.h. Per-frame code (called once
 * per kernel call), so integer only like the rest of rte_frame_sources. */
#include "rtedge/cpu.h"

#include <stdlib.h>

#if defined(__aarch64__) && defined(__linux__)
#include <sys/auxv.h>
#ifndef HWCAP_ASIMD
#define HWCAP_ASIMD (1 << 1)
#endif
#endif

uint32_t rte_cpu_features_hw(void)
{
    uint32_t f = 0;
#if defined(__x86_64__) || defined(__i386__)
    /* cheap after the first call: libgcc fills __cpu_model once */
    __builtin_cpu_init();
    if (__builtin_cpu_supports("sse2"))
        f |= RTE_CPU_X86_SSE2;
    if (__builtin_cpu_supports("ssse3"))
        f |= RTE_CPU_X86_SSSE3;
    if (__builtin_cpu_supports("sse4.1"))
        f |= RTE_CPU_X86_SSE41;
    /* __builtin_cpu_supports("avx2") also checks that the OS saves the
     * ymm registers (XGETBV), so a VM without AVX state gets SSSE3 */
    if (__builtin_cpu_supports("avx2"))
        f |= RTE_CPU_X86_AVX2;
    /* likewise the zmm and mask registers' state for AVX-512 */
    if (__builtin_cpu_supports("avx512f") && __builtin_cpu_supports("avx512bw") &&
        __builtin_cpu_supports("avx512vl"))
        f |= RTE_CPU_X86_AVX512;
#elif defined(__aarch64__) && defined(__linux__)
    if (getauxval(AT_HWCAP) & HWCAP_ASIMD)
        f |= RTE_CPU_ARM_NEON;
#elif defined(__aarch64__)
    f |= RTE_CPU_ARM_NEON; /* mandatory in the AArch64 base ABI */
#endif
    return f;
}

uint32_t rte_cpu_features(void)
{
    const char *force = getenv("RTE_FORCE_C");
    if (force && force[0] && !(force[0] == '0' && force[1] == '\0'))
        return 0;
    return rte_cpu_features_hw();
}
