// ATTENUVIS_MIE_CLONES: compile a function once per x86-64 instruction-set
// level (AVX-512, AVX2, baseline) and let the loader pick the best the CPU
// runs.  Private to the mie library.  The library is built with
// -ffp-contract=off (mie/CMakeLists.txt), so every clone performs the same
// IEEE operations in the same order and returns the same bits; only the
// vector width differs.  Other compilers and targets get one plain function.
#pragma once

#if defined(__GNUC__) && !defined(__clang__) && defined(__x86_64__) && defined(__linux__)
#define ATTENUVIS_MIE_CLONES __attribute__((target_clones("arch=x86-64-v4", "arch=x86-64-v3", "default")))
#else
#define ATTENUVIS_MIE_CLONES
#endif
