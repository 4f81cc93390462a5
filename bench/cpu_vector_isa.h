#pragma once
// The widest x86 vector instruction set this CPU offers, as the peer benchmarks print it beside
// exact/Embree: Embree (Debian's libembree-dev) picks its kernels at run time, up to AVX-512,
// while shadowcert is built for baseline x86-64 (-ffp-contract=off; a build for x86-64-v3 was
// measured to gain nothing: docs/diff.md#scaling), so the ratio depends on the CPU it is
// measured on. Figures from two machines compare only where this line agrees.
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

}  // namespace shadowcert::bench
