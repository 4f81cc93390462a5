# shadowcert_module(NAME [PUBLIC targets...] [PRIVATE targets...] [CGAL_PCH OWNER])
#
# One static library, shadowcert_NAME, of the calling folder's *.cpp and detail/*.cpp. A
# folder's top-level headers are its interface; detail/ holds headers only its own sources
# (and its own tests) include, which tests/layering_test.py enforces.
#
# The shadowcert modules named in PUBLIC and PRIVATE must be among the arrows that the top
# CMakeLists.txt allows for NAME (SHADOWCERT_ALLOWED_NAME); configuring fails otherwise, so
# the stated architecture and the link lines cannot drift apart. PUBLIC: the module's own
# headers include it; PRIVATE: only its sources do.
#
# CGAL_PCH OWNER (build time, docs/development.md#build-time): the sources that include a CGAL
# header (`#include <CGAL/...`, read when configuring) get CGAL's Epick kernel precompiled,
# which saves each about 3.5 s of parsing; the module's other sources are compiled as before.
# OWNER NAME builds the precompiled header; OWNER another module reuses that one's, which
# needs the same compile flags (CGAL::CGAL and shadowcert_warnings linked, no flags of its own).
function(shadowcert_module name)
  cmake_parse_arguments(ARG "" "CGAL_PCH" "PUBLIC;PRIVATE" ${ARGN})
  foreach(dependency IN LISTS ARG_PUBLIC ARG_PRIVATE)
    if(dependency MATCHES "^shadowcert_(.+)$" AND CMAKE_MATCH_1 IN_LIST SHADOWCERT_MODULES)
      set(module "${CMAKE_MATCH_1}")
      if(NOT module IN_LIST SHADOWCERT_ALLOWED_${name})
        message(FATAL_ERROR "shadowcert_${name} may not link ${dependency}: the top CMakeLists.txt "
                            "allows ${name} -> ${SHADOWCERT_ALLOWED_${name}}")
      endif()
    endif()
  endforeach()
  file(GLOB sources CONFIGURE_DEPENDS ${CMAKE_CURRENT_SOURCE_DIR}/*.cpp ${CMAKE_CURRENT_SOURCE_DIR}/detail/*.cpp)
  add_library(shadowcert_${name} STATIC ${sources})
  # The build's own helper targets (shadowcert_warnings, shadowcert_fuzz_coverage: flags only)
  # are linked for the build tree only. A static library's private links still reach its
  # installed export as $<LINK_ONLY:...> (cmake/ShadowcertInstall.cmake), and these must not:
  # a consumer of the package gets neither our warnings nor libFuzzer's instrumentation.
  set(private_links)
  foreach(dependency IN LISTS ARG_PRIVATE)
    if(dependency MATCHES "^shadowcert_(.+)$" AND NOT CMAKE_MATCH_1 IN_LIST SHADOWCERT_MODULES)
      list(APPEND private_links "$<BUILD_INTERFACE:${dependency}>")
    else()
      list(APPEND private_links "${dependency}")
    endif()
  endforeach()
  target_link_libraries(shadowcert_${name} PUBLIC ${ARG_PUBLIC}
                        PRIVATE $<BUILD_INTERFACE:shadowcert_warnings> ${private_links})
  if(ARG_CGAL_PCH AND SHADOWCERT_PRECOMPILE_CGAL)
    if(ARG_CGAL_PCH STREQUAL name)
      target_precompile_headers(shadowcert_${name} PRIVATE <CGAL/Exact_predicates_inexact_constructions_kernel.h>)
    else()
      target_precompile_headers(shadowcert_${name} REUSE_FROM shadowcert_${ARG_CGAL_PCH})
    endif()
    foreach(source IN LISTS sources)
      file(STRINGS ${source} cgal_include REGEX "^#include <CGAL/" LIMIT_COUNT 1)
      if(NOT cgal_include)
        set_source_files_properties(${source} PROPERTIES SKIP_PRECOMPILE_HEADERS ON)
      endif()
    endforeach()
  endif()
endfunction()
