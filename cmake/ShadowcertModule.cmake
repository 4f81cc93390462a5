# shadowcert_module(NAME [PUBLIC targets...] [PRIVATE targets...])
#
# One static library, shadowcert_NAME, of the calling folder's *.cpp and detail/*.cpp. A
# folder's top-level headers are its interface; detail/ holds headers only its own sources
# (and its own tests) include, which tests/layering_test.py enforces.
#
# The shadowcert modules named in PUBLIC and PRIVATE must be among the arrows that the top
# CMakeLists.txt allows for NAME (SHADOWCERT_ALLOWED_NAME); configuring fails otherwise, so
# the stated architecture and the link lines cannot drift apart. PUBLIC: the module's own
# headers include it; PRIVATE: only its sources do.
function(shadowcert_module name)
  cmake_parse_arguments(ARG "" "" "PUBLIC;PRIVATE" ${ARGN})
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
  target_link_libraries(shadowcert_${name} PUBLIC ${ARG_PUBLIC} PRIVATE shadowcert_warnings ${ARG_PRIVATE})
endfunction()
