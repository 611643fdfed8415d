#pragma once
// Function multi-versioning for the row kernels (face_flux_rows.cpp, cell_rows.cpp).
// Each kernel marked AVALANCHE_SIMD_CLONES is compiled for several instruction sets
// and the best one the processor has is chosen when the program loads: the default
// build stays portable (no -march), and on AVX-512 or AVX2 machines the loops run 8
// or 4 lanes per instruction. The AVX-512 version is for x86-64-v4 (AVX-512F with BW,
// DQ, VL), whose byte vectors let loops over one-byte flags vectorise (rest_faces.cpp);
// a processor with AVX-512F alone gets the AVX2 version. Every version gives the same
// bits: IEEE +, -, *, / and sqrt are exactly rounded and the core layer is built
// without FMA contraction.
// Other compilers (the clang sanitizer and fuzzing builds) get the portable version.
#if defined(__GNUC__) && !defined(__clang__) && defined(__x86_64__) && !defined(AVALANCHE_NO_CLONES)
#define AVALANCHE_SIMD_CLONES __attribute__((target_clones("default", "avx2", "arch=x86-64-v4")))
#else
#define AVALANCHE_SIMD_CLONES
#endif

// The lane functions must be inlined into each clone to be compiled for its ISA.
#define AVALANCHE_INLINE inline __attribute__((always_inline))
