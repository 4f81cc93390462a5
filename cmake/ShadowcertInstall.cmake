# `cmake --install` (docs/development.md#install-and-use-as-a-package): the `shadowcert`
# executable, the docs, and the CMake package `shadowcert` with the exact and GL libraries.
#
#   <prefix>/bin/shadowcert
#   <prefix>/share/doc/shadowcert/README.md, docs/*.md      (the source tree's layout: links work)
#   <prefix>/include/shadowcert/<module>/*.h                  (#include "exact/edge_multiplicity.h")
#   <prefix>/lib/libshadowcert_<module>.a
#   <prefix>/lib/cmake/shadowcert/shadowcertConfig.cmake      (find_package(shadowcert))
#
# The package exports shadowcert::exact, shadowcert::volume and shadowcert::gpu and every module they link, public
# or private (static libraries: a consumer links the private ones too), computed below from
# the link lines, so a new arrow in the top CMakeLists.txt cannot leave the export incomplete.
# Nothing of tests/, bench/ or fuzz/ is installed. Included by the top CMakeLists.txt after
# every module is defined; the tests/package/ test installs into a scratch prefix and builds a
# consumer against it.
include(CMakePackageConfigHelpers)

# A function only for its scope: none of its variables reaches tests/ or bench/.
function(shadowcert_install_package)

  set(SHADOWCERT_PACKAGE_MODULES exact volume gpu pipeline)  # what the package is for; the rest follows
  set(SHADOWCERT_PACKAGE_CMAKE_DIR ${CMAKE_INSTALL_LIBDIR}/cmake/shadowcert)
  set(SHADOWCERT_PACKAGE_INCLUDE_DIR ${CMAKE_INSTALL_INCLUDEDIR}/shadowcert)  # also core/CMakeLists.txt

  # ---- the exported modules: the closure of exact, volume and gpu over their shadowcert_* links
  set(exported)
  set(pending ${SHADOWCERT_PACKAGE_MODULES})
  while(pending)
    list(POP_FRONT pending module)
    if(module IN_LIST exported)
      continue()
    endif()
    list(APPEND exported ${module})
    get_target_property(type shadowcert_${module} TYPE)
    if(type STREQUAL "INTERFACE_LIBRARY")
      get_target_property(links shadowcert_${module} INTERFACE_LINK_LIBRARIES)
    else()
      get_target_property(links shadowcert_${module} LINK_LIBRARIES)  # public and private
    endif()
    foreach(link IN LISTS links)
      if(link MATCHES "^shadowcert_(.+)$" AND CMAKE_MATCH_1 IN_LIST SHADOWCERT_MODULES)
        list(APPEND pending ${CMAKE_MATCH_1})
      endif()
    endforeach()
  endwhile()
  list(SORT exported)

  # ---- the exported targets: shadowcert::<module>
  foreach(module IN LISTS exported)
    set_target_properties(shadowcert_${module} PROPERTIES EXPORT_NAME ${module})
    list(APPEND exported_targets shadowcert_${module})
  endforeach()

  # What the build gets from directory-wide settings (the top CMakeLists.txt) and a consumer of
  # the installed libraries must get as well, on shadowcert::core, which every module links:
  # - no FMA contraction: core/light_side_formula.h and the other float code of core/ are
  #   header-only, so they are compiled in the consumer's files and must round as in ours;
  # - with SHADOWCERT_SANITIZE, the libraries call the ASan and UBSan runtimes: a program that
  #   links them links those too (same compiler as the build; compile flags stay the consumer's).
  # $<INSTALL_INTERFACE:...> only: the build tree's command lines do not change.
  target_compile_options(shadowcert_core INTERFACE
    $<INSTALL_INTERFACE:$<$<CXX_COMPILER_ID:GNU,Clang>:-ffp-contract=off>>)
  if(SHADOWCERT_SANITIZE)
    target_link_options(shadowcert_core INTERFACE $<INSTALL_INTERFACE:-fsanitize=address,undefined>)
  endif()

  install(TARGETS ${exported_targets} EXPORT shadowcertTargets
          ARCHIVE DESTINATION ${CMAKE_INSTALL_LIBDIR})
  install(EXPORT shadowcertTargets NAMESPACE shadowcert:: DESTINATION ${SHADOWCERT_PACKAGE_CMAKE_DIR})

  # ---- headers: each exported module's top-level headers (its interface), and the detail/
  # headers that those include (gpu/edge_map.h includes gpu/detail/render_texture.h), found by
  # reading the #include lines at configure time, to a fixed point. An installed header that
  # includes a header of a module outside the package, or one generated at build time, is an
  # error here. The package test checks the installed tree the same way at install time.
  set(headers)
  foreach(module IN LISTS exported)
    file(GLOB module_headers CONFIGURE_DEPENDS ${PROJECT_SOURCE_DIR}/${module}/*.h)
    list(APPEND headers ${module_headers})
  endforeach()
  set(pending ${headers})
  while(pending)
    list(POP_FRONT pending header)
    file(STRINGS ${header} includes REGEX "^[ \t]*#[ \t]*include[ \t]*\"[^\"]+\"")
    foreach(line IN LISTS includes)
      string(REGEX REPLACE "^[^\"]*\"([^\"]+)\".*$" "\\1" included "${line}")
      string(REGEX MATCH "^[^/]+" included_module "${included}")
      if(NOT included_module IN_LIST SHADOWCERT_MODULES)
        continue()  # not a project header
      endif()
      file(RELATIVE_PATH where ${PROJECT_SOURCE_DIR} ${header})
      if(NOT included_module IN_LIST exported)
        message(FATAL_ERROR "${where} includes \"${included}\", but ${included_module} is not in the "
                            "installed package (${exported}): cmake/ShadowcertInstall.cmake")
      endif()
      if(NOT EXISTS ${PROJECT_SOURCE_DIR}/${included})
        message(FATAL_ERROR "${where} includes \"${included}\", which is not in the source tree "
                            "(generated?): the installed package would lack it")
      endif()
      if(NOT ${PROJECT_SOURCE_DIR}/${included} IN_LIST headers)
        list(APPEND headers ${PROJECT_SOURCE_DIR}/${included})
        list(APPEND pending ${PROJECT_SOURCE_DIR}/${included})
      endif()
    endforeach()
  endwhile()
  foreach(header IN LISTS headers)
    file(RELATIVE_PATH relative ${PROJECT_SOURCE_DIR} ${header})
    get_filename_component(folder ${relative} DIRECTORY)
    install(FILES ${header} DESTINATION ${SHADOWCERT_PACKAGE_INCLUDE_DIR}/${folder})
  endforeach()

  # ---- the package files: shadowcertConfig.cmake finds the third-party libraries the exported
  # ones link (mirroring the top CMakeLists.txt), then includes shadowcertTargets.cmake.
  configure_package_config_file(${PROJECT_SOURCE_DIR}/cmake/shadowcertConfig.cmake.in
    ${PROJECT_BINARY_DIR}/package/shadowcertConfig.cmake
    INSTALL_DESTINATION ${SHADOWCERT_PACKAGE_CMAKE_DIR})
  # 0.x: a minor version may change the interface.
  write_basic_package_version_file(${PROJECT_BINARY_DIR}/package/shadowcertConfigVersion.cmake
    COMPATIBILITY SameMinorVersion)
  install(FILES ${PROJECT_BINARY_DIR}/package/shadowcertConfig.cmake
                ${PROJECT_BINARY_DIR}/package/shadowcertConfigVersion.cmake
          DESTINATION ${SHADOWCERT_PACKAGE_CMAKE_DIR})

  # ---- the executable and the docs (README.md's links to docs/ keep working)
  install(TARGETS shadowcert RUNTIME DESTINATION ${CMAKE_INSTALL_BINDIR})
  file(GLOB docs CONFIGURE_DEPENDS ${PROJECT_SOURCE_DIR}/docs/*.md)
  install(FILES ${PROJECT_SOURCE_DIR}/README.md DESTINATION ${CMAKE_INSTALL_DOCDIR})
  install(FILES ${docs} DESTINATION ${CMAKE_INSTALL_DOCDIR}/docs)
endfunction()

shadowcert_install_package()
