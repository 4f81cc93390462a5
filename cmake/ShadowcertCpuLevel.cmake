# The x86-64 microarchitecture level the project's code is compiled for (docs/development.md#cpu-level).
#
# SHADOWCERT_CPU_LEVEL:
#   auto       (default) the highest of x86-64-v4 (AVX-512), x86-64-v3 (AVX2, FMA, BMI2) and
#              x86-64-v2 (SSE4.2, POPCNT) that the compiler accepts and this machine runs: a build
#              from source is for the machine that builds it, as Embree picks its kernels for the
#              CPU it runs on;
#   baseline   any x86-64 (what a package for other machines wants);
#   x86-64-v2, x86-64-v3, x86-64-v4: that level, whatever this machine runs.
# No answer depends on the level: contraction is off everywhere (-ffp-contract=off, top
# CMakeLists.txt), so every double is rounded operation by operation at every level, and the
# inputs that define an exact answer come from core/portable_math.h, not from libm.
#
# Sets SHADOWCERT_CPU_MARCH: the -march level compiled for, empty for baseline; and
# SHADOWCERT_CODE_LEVEL: that level's name, or "baseline" (what configuring and the benchmarks print).

set(SHADOWCERT_CPU_LEVEL auto CACHE STRING
    "x86-64 level the project's code is compiled for: auto, baseline, x86-64-v2, x86-64-v3 or x86-64-v4")
set_property(CACHE SHADOWCERT_CPU_LEVEL PROPERTY STRINGS auto baseline x86-64-v2 x86-64-v3 x86-64-v4)

set(SHADOWCERT_CPU_MARCH "")
if(SHADOWCERT_CPU_LEVEL STREQUAL "auto")
  if(CMAKE_SYSTEM_PROCESSOR MATCHES "^(x86_64|AMD64|amd64)$" AND NOT CMAKE_CROSSCOMPILING
     AND CMAKE_CXX_COMPILER_ID MATCHES "GNU|Clang")
    include(CheckCXXSourceRuns)
    # Per level, features that __builtin_cpu_supports names in GCC 12 and clang 14 alike. A test
    # program built for a level this CPU lacks may also die on its first instruction: that counts
    # as "does not run" too.
    set(features_x86-64-v4 avx512f avx512bw avx512cd avx512dq avx512vl avx2 fma bmi2)
    set(features_x86-64-v3 avx2 fma bmi bmi2 popcnt sse4.2)
    set(features_x86-64-v2 popcnt sse4.2 ssse3)
    foreach(level x86-64-v4 x86-64-v3 x86-64-v2)
      set(checks "")
      foreach(feature ${features_${level}})
        string(APPEND checks " && __builtin_cpu_supports(\"${feature}\")")
      endforeach()
      string(REPLACE "-" "_" result "SHADOWCERT_CPU_RUNS_${level}")
      set(CMAKE_REQUIRED_FLAGS "-march=${level}")
      set(CMAKE_REQUIRED_QUIET ON)
      check_cxx_source_runs("int main() { __builtin_cpu_init(); return (1${checks}) ? 0 : 1; }" ${result})
      unset(CMAKE_REQUIRED_FLAGS)
      unset(CMAKE_REQUIRED_QUIET)
      if(${result})
        set(SHADOWCERT_CPU_MARCH ${level})
        break()
      endif()
    endforeach()
  endif()
elseif(SHADOWCERT_CPU_LEVEL MATCHES "^x86-64-v[234]$")
  set(SHADOWCERT_CPU_MARCH ${SHADOWCERT_CPU_LEVEL})
elseif(NOT SHADOWCERT_CPU_LEVEL STREQUAL "baseline")
  message(FATAL_ERROR "SHADOWCERT_CPU_LEVEL is '${SHADOWCERT_CPU_LEVEL}': expected auto, baseline, x86-64-v2, "
                      "x86-64-v3 or x86-64-v4")
endif()

set(SHADOWCERT_CODE_LEVEL baseline)
if(SHADOWCERT_CPU_MARCH)
  add_compile_options(-march=${SHADOWCERT_CPU_MARCH})
  set(SHADOWCERT_CODE_LEVEL ${SHADOWCERT_CPU_MARCH})
endif()
message(STATUS "shadowcert: code compiled for ${SHADOWCERT_CODE_LEVEL} (SHADOWCERT_CPU_LEVEL=${SHADOWCERT_CPU_LEVEL})")
