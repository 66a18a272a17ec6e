#pragma once
// GEOTANDEM_AVX2_CLONES marks a hot loop for an AVX2 copy beside the default one, chosen at run time
// by the processor (GCC's target_clones, an ifunc): the same operations in the same order, so the
// values do not depend on the machine. Under the thread sanitizer the function stays plain: the
// dynamic loader runs ifunc resolvers before that sanitizer's runtime is up, and the process dies
// at start.
#if defined(__SANITIZE_THREAD__)
#define GEOTANDEM_AVX2_CLONES
#else
#define GEOTANDEM_AVX2_CLONES [[gnu::target_clones("avx2", "default")]]
#endif
