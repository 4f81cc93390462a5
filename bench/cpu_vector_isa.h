#pragma once
// The widest x86 vector instruction set this CPU offers, and the x86-64 level shadowcert's code
// was compiled for, as the peer benchmarks print them beside exact/Embree: Embree (Debian's
// libembree-dev) picks its kernels at run time, up to AVX-512, and shadowcert is compiled for
// the level SHADOWCERT_CPU_LEVEL names (by default the highest the building machine runs:
// cmake/ShadowcertCpuLevel.cmake, docs/development.md#cpu-level), so the ratio depends on the
// CPU it is measured on. Figures from two machines compare only where this line agrees.
namespace shadowcert::bench {

inline const char* cpu_vector_isa() {
#if (defined(__GNUC__) || defined(__clang__)) && (defined(__x86_64__) || defined(__i386__))
  if (__builtin_cpu_supports("avx512f")) return "avx512f";
  if (__builtin_cpu_supports("avx2")) return "avx2";
  if (__builtin_cpu_supports("avx")) return "avx";
  return "sse2";
#else
  return "not x86";
#endif
}

// The level the benchmark's code was compiled for ("baseline": any x86-64), as bench/CMakeLists.txt
// defines it from cmake/ShadowcertCpuLevel.cmake.
inline const char* code_level() { return SHADOWCERT_CODE_LEVEL; }

}  // namespace shadowcert::bench
