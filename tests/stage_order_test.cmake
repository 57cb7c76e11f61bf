# The stage-order check itself (cmake/stage_order.cmake): on a small tree, an include
# from a stage to a later one must fail the check and be named, and so must a printer's
# include of a solving header; includes downward, in either spelling, must pass.
#   cmake -DSOURCE_DIR=<kinema> -DWORK_DIR=<scratch> -P tests/stage_order_test.cmake
file(REMOVE_RECURSE "${WORK_DIR}")
file(MAKE_DIRECTORY "${WORK_DIR}/engine/numeric" "${WORK_DIR}/engine/printers")
file(WRITE "${WORK_DIR}/engine/printers/table.cpp"
     "#include \"engine/numeric/motion_table.hpp\"\n#include <kinema/engine/base/errors.hpp>\n")
file(WRITE "${WORK_DIR}/engine/numeric/motion_table.hpp" "#pragma once\n#include \"engine/base/errors.hpp\"\n")
file(WRITE "${WORK_DIR}/engine/numeric/sweep.hpp" "#pragma once\n#include \"engine/numeric/motion_table.hpp\"\n")
execute_process(COMMAND "${CMAKE_COMMAND}" -DROOT=${WORK_DIR} -P ${SOURCE_DIR}/cmake/stage_order.cmake
                RESULT_VARIABLE status ERROR_VARIABLE error)
if(NOT status EQUAL 0)
  message(FATAL_ERROR "includes from later stages to earlier ones were refused:\n${error}")
endif()

file(APPEND "${WORK_DIR}/engine/numeric/sweep.hpp" "#include \"engine/printers/table.hpp\"\n")
execute_process(COMMAND "${CMAKE_COMMAND}" -DROOT=${WORK_DIR} -P ${SOURCE_DIR}/cmake/stage_order.cmake
                RESULT_VARIABLE status ERROR_VARIABLE error)
string(REGEX REPLACE "[ \n]+" " " error "${error}")  # CMake wraps its messages
if(status EQUAL 0 OR NOT error MATCHES "engine/numeric/sweep.hpp \\(numeric\\) includes engine/printers/table.hpp \\(printers\\)")
  message(FATAL_ERROR "an include from numeric to printers passed the check (status ${status}):\n${error}")
endif()

# A printer that includes a solving header (here the sweep, which solves values) fails:
# a printer formats what the analysis computed, it does not solve.
file(WRITE "${WORK_DIR}/engine/numeric/sweep.hpp" "#pragma once\n#include \"engine/numeric/motion_table.hpp\"\n")
file(APPEND "${WORK_DIR}/engine/printers/table.cpp" "#include \"engine/numeric/sweep.hpp\"\n")
execute_process(COMMAND "${CMAKE_COMMAND}" -DROOT=${WORK_DIR} -P ${SOURCE_DIR}/cmake/stage_order.cmake
                RESULT_VARIABLE status ERROR_VARIABLE error)
string(REGEX REPLACE "[ \n]+" " " error "${error}")
if(status EQUAL 0 OR NOT error MATCHES "engine/printers/table.cpp \\(printers\\) includes engine/numeric/sweep.hpp, a solving header")
  message(FATAL_ERROR "a printer including a solving header passed the check (status ${status}):\n${error}")
endif()
# The front ends: a front end writes the constraints stage's types (a producer includes
# what it produces), and a reader, which gives what the user wrote, runs no front end.
file(MAKE_DIRECTORY "${WORK_DIR}/readers" "${WORK_DIR}/linkages" "${WORK_DIR}/engine/constraints")
file(REMOVE "${WORK_DIR}/engine/numeric/sweep.hpp" "${WORK_DIR}/engine/printers/table.cpp")
file(WRITE "${WORK_DIR}/engine/constraints/constraint_system.hpp" "#pragma once\n")
file(WRITE "${WORK_DIR}/linkages/dyads.cpp"
     "#include \"engine/constraints/constraint_system.hpp\"\n#include \"readers/mechanism.hpp\"\n")
file(WRITE "${WORK_DIR}/readers/mechanism_file.cpp" "#include \"engine/base/errors.hpp\"\n")
execute_process(COMMAND "${CMAKE_COMMAND}" -DROOT=${WORK_DIR} -P ${SOURCE_DIR}/cmake/stage_order.cmake
                RESULT_VARIABLE status ERROR_VARIABLE error)
if(NOT status EQUAL 0)
  message(FATAL_ERROR "a front end's includes of the reader's and the constraints' headers were refused:\n${error}")
endif()
file(APPEND "${WORK_DIR}/readers/mechanism_file.cpp" "#include \"linkages/dyads.hpp\"\n")
execute_process(COMMAND "${CMAKE_COMMAND}" -DROOT=${WORK_DIR} -P ${SOURCE_DIR}/cmake/stage_order.cmake
                RESULT_VARIABLE status ERROR_VARIABLE error)
string(REGEX REPLACE "[ \n]+" " " error "${error}")
if(status EQUAL 0 OR NOT error MATCHES "readers/mechanism_file.cpp \\(readers\\) includes linkages/dyads.hpp \\(front ends\\)")
  message(FATAL_ERROR "a reader that runs a front end passed the check (status ${status}):\n${error}")
endif()

# A pending upward include that the tree no longer has is named, so the list only shrinks.
# The tree's own list is empty; this small tree gives one entry (-DPENDING): engine/model.cpp
# including an analysis header, while here it includes only a header of its own stage or below.
set(pending "-DPENDING=engine/model.cpp -> engine/analysis/output_scale.hpp")
file(REMOVE "${WORK_DIR}/readers/mechanism_file.cpp")
file(WRITE "${WORK_DIR}/engine/model.cpp" "#include \"engine/base/errors.hpp\"\n")
execute_process(COMMAND "${CMAKE_COMMAND}" -DROOT=${WORK_DIR} "${pending}" -P ${SOURCE_DIR}/cmake/stage_order.cmake
                RESULT_VARIABLE status ERROR_VARIABLE error)
string(REGEX REPLACE "[ \n]+" " " error "${error}")
if(status EQUAL 0 OR NOT error MATCHES "pending \"engine/model.cpp -> engine/analysis/output_scale.hpp\" is no longer an upward include")
  message(FATAL_ERROR "a pending entry the tree no longer needs passed the check (status ${status}):\n${error}")
endif()
file(APPEND "${WORK_DIR}/engine/model.cpp" "#include \"engine/analysis/output_scale.hpp\"\n")
execute_process(COMMAND "${CMAKE_COMMAND}" -DROOT=${WORK_DIR} "${pending}" -P ${SOURCE_DIR}/cmake/stage_order.cmake
                RESULT_VARIABLE status ERROR_VARIABLE error)
if(NOT status EQUAL 0)
  message(FATAL_ERROR "the pending upward include, present, was refused:\n${error}")
endif()
# Without that entry (the tree's own list, empty) the same include fails.
execute_process(COMMAND "${CMAKE_COMMAND}" -DROOT=${WORK_DIR} -P ${SOURCE_DIR}/cmake/stage_order.cmake
                RESULT_VARIABLE status ERROR_VARIABLE error)
string(REGEX REPLACE "[ \n]+" " " error "${error}")
if(status EQUAL 0 OR NOT error MATCHES "engine/model.cpp \\(model\\) includes engine/analysis/output_scale.hpp \\(analysis\\)")
  message(FATAL_ERROR "the model's include of an analysis header passed the check with the tree's own pending list (status ${status}):\n${error}")
endif()

# A program's spelling of the facade, <kinema/kinema.hpp>, is the facade's stage: the base
# including it fails; <kinema/error.hpp> is the base's own error, which any stage may include.
file(WRITE "${WORK_DIR}/engine/model.cpp" "#include \"engine/base/errors.hpp\"\n")
file(WRITE "${WORK_DIR}/engine/base/errors.hpp" "#pragma once\n#include <kinema/error.hpp>\n")
execute_process(COMMAND "${CMAKE_COMMAND}" -DROOT=${WORK_DIR} -P ${SOURCE_DIR}/cmake/stage_order.cmake
                RESULT_VARIABLE status ERROR_VARIABLE error)
if(NOT status EQUAL 0)
  message(FATAL_ERROR "the base's include of <kinema/error.hpp> was refused:\n${error}")
endif()
file(APPEND "${WORK_DIR}/engine/base/errors.hpp" "#include <kinema/kinema.hpp>\n")
execute_process(COMMAND "${CMAKE_COMMAND}" -DROOT=${WORK_DIR} -P ${SOURCE_DIR}/cmake/stage_order.cmake
                RESULT_VARIABLE status ERROR_VARIABLE error)
string(REGEX REPLACE "[ \n]+" " " error "${error}")
if(status EQUAL 0 OR NOT error MATCHES "engine/base/errors.hpp \\(base\\) includes api/kinema/kinema.hpp \\(facade\\)")
  message(FATAL_ERROR "the base's include of <kinema/kinema.hpp> passed the check (status ${status}):\n${error}")
endif()
