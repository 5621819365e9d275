/* CPU features for the SIMD row kernels (libyuv style: each kernel has a
 * plain C reference and SIMD variants that give the same bytes; the variant
 * is chosen at run time).
 *
 * No state is kept: rte_cpu_features() asks the CPU (cpuid through
 * __builtin_cpu_supports on x86, getauxval(AT_HWCAP) on aarch64) and reads
 * the environment variable RTE_FORCE_C on every call. The kernels call it
 * once per image (not per row), so the cost (a few bit tests and one
 * getenv, well under a microsecond) is noise beside a frame, it is safe
 * from any thread, and setting RTE_FORCE_C takes effect at the next call.
 * (Like every getenv, it must not race with a setenv in another thread.) */
#ifndef RTEDGE_CPU_H
#define RTEDGE_CPU_H

#include <stdint.h>

#include "rtedge/status.h"

#ifdef __cplusplus
extern "C" {
#endif

enum {
    RTE_CPU_X86_SSE2 = 1u << 0,
    RTE_CPU_X86_SSSE3 = 1u << 1,
    RTE_CPU_X86_SSE41 = 1u << 2,
    RTE_CPU_X86_AVX2 = 1u << 3,
    RTE_CPU_X86_AVX512 = 1u << 4, /* AVX-512 F, BW and VL, with the OS saving their state */
    RTE_CPU_ARM_NEON = 1u << 8,   /* AdvSIMD (ASIMD), always present on aarch64 Linux */
};

/* The RTE_CPU_* bits of this CPU that rtedge can use, or 0 when the
 * environment variable RTE_FORCE_C is set to a value other than "" or "0"
 * (every kernel then runs its plain C reference). */
RTE_API uint32_t rte_cpu_features(void);

/* The same bits without looking at RTE_FORCE_C (what the hardware has;
 * tests use it to run every variant the CPU supports). */
RTE_API uint32_t rte_cpu_features_hw(void);

#ifdef __cplusplus
}
#endif
#endif
