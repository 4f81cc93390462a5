# The ctest test `package_consumer` (label package; tests/CMakeLists.txt), run with cmake -P:
# installs the build into a scratch prefix as a user would, checks what is there, then
# configures, builds and runs tests/package/consumer/ against it with find_package(shadowcert).
#
#   -DBUILD_DIR=    the build tree to install (already built: cmake --install builds nothing)
#   -DWORK_DIR=     scratch folder, emptied first: WORK_DIR/prefix and WORK_DIR/consumer
#   -DCONSUMER_DIR= tests/package/consumer
#   -DVERSION=      the project's version (`shadowcert --version` must print it)
#   -DGENERATOR= -DMAKE_PROGRAM= -DCXX_COMPILER= -DCONFIG=   the build tree's, for the consumer
#   -DPREFIX_PATH=  the build tree's CMAKE_PREFIX_PATH, '|'-separated (may be empty)
#   -DBINDIR= -DLIBDIR= -DINCLUDEDIR= -DDOCDIR=   its GNUInstallDirs folders (bin, lib, ...)
#
# The consumer gets the build's compiler, and nothing of its flags: what a program linking the
# libraries needs (the sanitizer runtimes of a SHADOWCERT_SANITIZE build, no FMA contraction)
# comes with the package's targets (cmake/ShadowcertInstall.cmake), which is what this checks.
# Any failure stops the script with the failing step's full output.
cmake_minimum_required(VERSION 3.22)

foreach(var BUILD_DIR WORK_DIR CONSUMER_DIR VERSION GENERATOR CXX_COMPILER BINDIR LIBDIR INCLUDEDIR DOCDIR)
  if(NOT DEFINED ${var} OR "${${var}}" STREQUAL "")
    message(FATAL_ERROR "package test: -D${var}=... is required")
  endif()
endforeach()

set(prefix ${WORK_DIR}/prefix)
set(consumer_build ${WORK_DIR}/consumer)
file(REMOVE_RECURSE ${WORK_DIR})
file(MAKE_DIRECTORY ${WORK_DIR})

set(config_args)
if(CONFIG)
  set(config_args --config ${CONFIG})
endif()

# Runs a command; on failure, stops with its output. Its output is in `step_output` after.
function(step name)
  string(TIMESTAMP start "%s")
  execute_process(COMMAND ${ARGN} RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE out)
  string(TIMESTAMP stop "%s")
  if(NOT rc EQUAL 0)
    list(JOIN ARGN " " command)
    message(FATAL_ERROR "package test: ${name} FAILED (exit ${rc})\n  ${command}\n${out}")
  endif()
  math(EXPR seconds "${stop} - ${start}")
  message(STATUS "package test: ${name}: ok (${seconds} s)")
  set(step_output "${out}" PARENT_SCOPE)
endfunction()

function(fail what)
  message(FATAL_ERROR "package test: ${what}")
endfunction()

# ---- 1. install
step("cmake --install ${BUILD_DIR} --prefix ${prefix}"
     ${CMAKE_COMMAND} --install ${BUILD_DIR} --prefix ${prefix} ${config_args})

# ---- 2. what the prefix holds
set(includes ${prefix}/${INCLUDEDIR}/shadowcert)
set(package ${LIBDIR}/cmake/shadowcert)
foreach(file ${BINDIR}/shadowcert ${DOCDIR}/README.md ${DOCDIR}/docs/development.md
             ${package}/shadowcertConfig.cmake ${package}/shadowcertConfigVersion.cmake
             ${package}/shadowcertTargets.cmake
             ${INCLUDEDIR}/shadowcert/exact/edge_multiplicity.h ${INCLUDEDIR}/shadowcert/volume/volume_workspace.h
             ${INCLUDEDIR}/shadowcert/gpu/camera_transform.h)
  if(NOT EXISTS ${prefix}/${file})
    fail("${prefix}/${file} was not installed")
  endif()
endforeach()
# Only the executable: no test or benchmark program.
file(GLOB programs RELATIVE ${prefix}/${BINDIR} ${prefix}/${BINDIR}/*)
if(NOT programs STREQUAL "shadowcert")
  fail("${prefix}/${BINDIR} holds '${programs}', expected only 'shadowcert'")
endif()
# The installed executable runs (its shared libraries resolve without the build tree).
step("shadowcert --version" ${prefix}/${BINDIR}/shadowcert --version)
if(NOT step_output MATCHES "shadowcert ${VERSION}")
  fail("shadowcert --version printed '${step_output}', expected 'shadowcert ${VERSION}'")
endif()
# Every project header an installed header includes is installed too (a detail/ header, a
# generated one), and none includes CGAL or OpenMesh (they stay inside the libraries).
file(GLOB_RECURSE headers RELATIVE ${includes} ${includes}/*)
list(LENGTH headers header_count)
foreach(header IN LISTS headers)
  file(STRINGS ${includes}/${header} lines REGEX "^[ \t]*#[ \t]*include")
  foreach(line IN LISTS lines)
    if(line MATCHES "<(CGAL|OpenMesh)/")
      fail("installed ${header} includes a private dependency: ${line}")
    endif()
    if(line MATCHES "\"([a-z_]+/[^\"]+)\"" AND NOT EXISTS ${includes}/${CMAKE_MATCH_1})
      fail("installed ${header} includes \"${CMAKE_MATCH_1}\", which is not installed")
    endif()
  endforeach()
endforeach()
message(STATUS "package test: the prefix holds shadowcert, the docs, the package files and "
               "${header_count} headers")

# ---- 3. a consumer: find_package(shadowcert), link shadowcert::exact, shadowcert::volume and shadowcert::gpu
string(REPLACE "|" ";" prefix_path "${prefix};${PREFIX_PATH}")
set(generator_args -G ${GENERATOR})
if(MAKE_PROGRAM)
  list(APPEND generator_args -DCMAKE_MAKE_PROGRAM=${MAKE_PROGRAM})
endif()
if(CONFIG)
  list(APPEND generator_args -DCMAKE_BUILD_TYPE=${CONFIG})
endif()
step("configure the consumer"
     ${CMAKE_COMMAND} -S ${CONSUMER_DIR} -B ${consumer_build} ${generator_args}
     -DCMAKE_CXX_COMPILER=${CXX_COMPILER} "-DCMAKE_PREFIX_PATH=${prefix_path}"
     -DCMAKE_FIND_PACKAGE_NO_PACKAGE_REGISTRY=ON)
# The package found is the one just installed, not another on the system.
file(STRINGS ${consumer_build}/CMakeCache.txt found REGEX "^shadowcert_DIR:")
string(REGEX REPLACE "^[^=]*=" "" found "${found}")
file(REAL_PATH "${found}" found)
file(REAL_PATH ${prefix}/${package} expected)
if(NOT found STREQUAL expected)
  fail("the consumer found shadowcert in '${found}', expected '${expected}'")
endif()
step("build the consumer" ${CMAKE_COMMAND} --build ${consumer_build} ${config_args})
set(program ${consumer_build}/consumer)
if(NOT EXISTS ${program} AND CONFIG)
  set(program ${consumer_build}/${CONFIG}/consumer)  # multi-config generators
endif()
step("run the consumer" ${program})
message(STATUS "${step_output}")
# The engine-style host: the host layer and pipeline/ from the installed package alone.
set(host ${consumer_build}/host)
if(NOT EXISTS ${host} AND CONFIG)
  set(host ${consumer_build}/${CONFIG}/host)
endif()
step("run the host" ${host})
message(STATUS "${step_output}")

# ---- 4. `import shadowcert` from the prefix (when the build has the module: -DPYTHON= the
# interpreter, -DPYTHON_DIR= the module's folder under the prefix): the installed module and stub
# load with nothing of the build tree on the path, and the module works (a tetrahedron certified,
# one frame of cs rendered headless).
if(PYTHON AND PYTHON_DIR)
  set(module_dir ${prefix}/${PYTHON_DIR})
  foreach(file shadowcert.pyi)
    if(NOT EXISTS ${module_dir}/${file})
      fail("${module_dir}/${file} was not installed")
    endif()
  endforeach()
  file(GLOB modules ${module_dir}/shadowcert*.so)
  if(NOT modules)
    fail("no shadowcert*.so in ${module_dir}")
  endif()
  set(check [=[
import sys, shadowcert
prefix = sys.argv[1]
assert shadowcert.__file__.startswith(prefix), shadowcert.__file__
vertices = [[0, 0, 0], [1, 0, 0], [0, 1, 0], [0, 0, 1]]
triangles = [[0, 2, 1], [0, 1, 3], [0, 3, 2], [1, 2, 3]]
report = shadowcert.certify(vertices, triangles, [0.2, 0.2, 5.0, 1.0], method="exact")
assert report["methods"]["exact"]["closed"] and report["methods"]["exact"]["count_failures"] == 0, report
frame = shadowcert.render(sys.argv[2], "cs", size=(64, 48))
assert frame["image"].shape == (48, 64, 4) and (frame["lit"] == 0).any()
print("import shadowcert from", shadowcert.__file__, "ok")
]=])
  step("import shadowcert from the prefix"
       ${CMAKE_COMMAND} -E env PYTHONPATH=${module_dir} PYTHONNOUSERSITE=1
       ${PYTHON} -c "${check}" ${prefix} ${SCENE})
  message(STATUS "${step_output}")
endif()
