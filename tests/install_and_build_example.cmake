# Run by ctest ("package: install, find_package(kinema) from examples/, run"):
# installs the build tree into a fresh prefix, checks that its headers are the
# facade's alone, builds examples/ as a project of its own against it
# (find_package(kinema)), runs the example and checks its omega3 against
# `kinema eval` at the same angles. Any failing step fails the test with its output.
#
#   cmake -DBUILD_DIR=<kinema build> -DSOURCE_DIR=<kinema source> -DWORK_DIR=<scratch>
#         -DCONFIG=<build type> -DCXX_COMPILER=<c++> -DGENERATOR=<generator>
#         -DLIBDIR=<CMAKE_INSTALL_LIBDIR> -DINCLUDEDIR=<CMAKE_INSTALL_INCLUDEDIR>
#         -DKINEMA=<the kinema program> [-DMAKE_PROGRAM=<make/ninja>]
#         [-DPYTHON=<python3> -DPYTHON_SITE=<the module's folder under the prefix>] -P install_and_build_example.cmake
# With PYTHON, the installed Python module is imported from the prefix and solves a value.
foreach(var BUILD_DIR SOURCE_DIR WORK_DIR CONFIG CXX_COMPILER GENERATOR LIBDIR INCLUDEDIR KINEMA)
  if(NOT DEFINED ${var} OR "${${var}}" STREQUAL "")
    message(FATAL_ERROR "install_and_build_example.cmake: -D${var}=... is required")
  endif()
endforeach()

set(prefix "${WORK_DIR}/prefix")
set(example_build "${WORK_DIR}/examples-build")
file(REMOVE_RECURSE "${WORK_DIR}")
file(MAKE_DIRECTORY "${WORK_DIR}")

# Runs one step; on failure stops with the command and everything it printed.
function(step name)
  list(JOIN ARGN " " command_line)
  message(STATUS "${name}: ${command_line}")
  execute_process(COMMAND ${ARGN} RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE out)
  if(NOT "${rc}" STREQUAL "0")
    message(FATAL_ERROR "${name} failed (${rc}):\n  ${command_line}\n${out}")
  endif()
  set(step_output "${out}" PARENT_SCOPE)
endfunction()

step("install" "${CMAKE_COMMAND}" --install "${BUILD_DIR}" --prefix "${prefix}" --config "${CONFIG}")
foreach(file ${LIBDIR}/cmake/kinema/kinemaConfig.cmake ${LIBDIR}/cmake/kinema/kinemaConfigVersion.cmake
             ${LIBDIR}/cmake/kinema/kinemaTargets.cmake ${INCLUDEDIR}/kinema/kinema.hpp)
  if(NOT EXISTS "${prefix}/${file}")
    message(FATAL_ERROR "not installed: ${prefix}/${file}")
  endif()
endforeach()
# The headers installed are the facade's (api/kinema/, and <kinema/error.hpp>, the base's
# error with nothing but <stdexcept>) and nothing else: no engine/ or loops/ header, which
# would name GiNaC and Eigen.
file(GLOB_RECURSE installed_headers LIST_DIRECTORIES true RELATIVE "${prefix}/${INCLUDEDIR}" "${prefix}/${INCLUDEDIR}/*")
file(GLOB_RECURSE facade_headers RELATIVE "${SOURCE_DIR}/api" "${SOURCE_DIR}/api/kinema/*.hpp")
list(APPEND facade_headers kinema kinema/error.hpp)  # the folder itself; the base's error (engine/base/error.hpp)
list(SORT installed_headers)
list(SORT facade_headers)
if(NOT installed_headers STREQUAL facade_headers)
  message(FATAL_ERROR "installed in ${prefix}/${INCLUDEDIR}: ${installed_headers}\n"
                      "expected the facade only: ${facade_headers}")
endif()

set(configure_args -S "${SOURCE_DIR}/examples" -B "${example_build}" -G "${GENERATOR}"
    "-DCMAKE_CXX_COMPILER=${CXX_COMPILER}" "-DCMAKE_BUILD_TYPE=${CONFIG}" "-DCMAKE_PREFIX_PATH=${prefix}"
    -DCMAKE_FIND_USE_PACKAGE_REGISTRY=OFF)
if(DEFINED MAKE_PROGRAM AND NOT "${MAKE_PROGRAM}" STREQUAL "")
  list(APPEND configure_args "-DCMAKE_MAKE_PROGRAM=${MAKE_PROGRAM}")
endif()
step("configure examples/" "${CMAKE_COMMAND}" ${configure_args})
# The package found must be the one just installed, not another kinema.
file(STRINGS "${example_build}/CMakeCache.txt" kinema_dir REGEX "^kinema_DIR:")
string(REGEX REPLACE "^kinema_DIR:[A-Z]*=" "" kinema_dir "${kinema_dir}")
file(REAL_PATH "${prefix}" real_prefix)
file(REAL_PATH "${kinema_dir}" real_kinema_dir)
string(FIND "${real_kinema_dir}" "${real_prefix}/" at)
if(NOT at EQUAL 0)
  message(FATAL_ERROR "examples/ found kinema in ${kinema_dir}, not in ${prefix}")
endif()

step("build examples/" "${CMAKE_COMMAND}" --build "${example_build}" --config "${CONFIG}")

set(program "${example_build}/library_usage")
if(NOT EXISTS "${program}")
  set(program "${example_build}/${CONFIG}/library_usage")  # multi-config generators
endif()
step("run library_usage" "${program}" "${SOURCE_DIR}/samples/four_bar.toml")
set(example_output "${step_output}")
message("${example_output}")

# The example's omega3 at each angle it prints is kinema eval's at those angles (both to
# 6 significant digits), so the value read by name is the right one.
string(REGEX MATCHALL "theta2 = [^:]+: omega3 = [^ ]+ rad/s" example_lines "${example_output}")
if(NOT example_lines)
  message(FATAL_ERROR "library_usage printed no \"theta2 = ...: omega3 = ... rad/s\"")
endif()
set(eval_args "")
set(angles "")
set(example_omega3 "")
foreach(line IN LISTS example_lines)
  string(REGEX REPLACE "^theta2 = ([^:]+): omega3 = ([^ ]+) rad/s$" "\\1;\\2" parts "${line}")
  list(GET parts 0 angle)
  list(GET parts 1 omega3)
  list(APPEND eval_args --at "${angle}")
  list(APPEND angles "${angle}")
  list(APPEND example_omega3 "${omega3}")
endforeach()
step("kinema eval" "${KINEMA}" eval "${SOURCE_DIR}/samples/four_bar.toml" ${eval_args})
string(REGEX MATCHALL "omega3 = [^ ]+ rad/s" eval_lines "${step_output}")
string(REGEX REPLACE "omega3 = ([^ ;]+) rad/s" "\\1" eval_omega3 "${eval_lines}")
if(NOT eval_omega3 STREQUAL example_omega3)
  list(JOIN angles ", " angles)
  list(JOIN example_omega3 ", " example_omega3)
  list(JOIN eval_omega3 ", " eval_omega3)
  message(FATAL_ERROR "omega3 (rad/s) at theta2 = ${angles}: library_usage printed ${example_omega3}, "
                      "kinema eval ${eval_omega3}")
endif()

# The Python module, where it was built: installed under the prefix, imported from there.
if(DEFINED PYTHON AND NOT "${PYTHON}" STREQUAL "")
  set(ENV{PYTHONPATH} "${prefix}/${PYTHON_SITE}")
  step("import the installed Python module" "${PYTHON}" -c
       "import kinema, pathlib; assert pathlib.Path(kinema.__file__).resolve().is_relative_to(pathlib.Path('${prefix}').resolve()), kinema.__file__; print(kinema.load('${SOURCE_DIR}/samples/four_bar.toml').at('30 deg')['omega3'])")
  message("${step_output}")
endif()
