# The stages of kinema, in the one direction the data flows: a stage's files may include
# their own stage's and earlier stages' headers, never a later stage's, so that every
# stage can be read (and tested, and reused by a new view) without the ones after it.
#
#   base          what every stage may use: errors, units and quantities, source locations,
#                 text safety, a run's input values
#   readers       what the user wrote: the three file forms and the --sweep syntax (readers/)
#   constraints   the hand-off, ConstraintSystem with its solving plan, and the GiNaC
#                 vocabulary that writes it: formulas read, symbols named, the chain rule
#   front ends    what builds a ConstraintSystem from what the user wrote: vector loops
#                 (loops/), joints and links (linkages/), spatial chains (chains/)
#   symbolic      derivation in GiNaC
#   numeric       per input value, no GiNaC
#   model         the derived and compiled mechanism
#   analysis      what views show beyond the solved table
#   problems      problem sets (variants drawn from a seed, checked, their answers) and answer checking (engine/problems/)
#   printers      formats only: what a view shows, from the results and the analysis
#   run           a long run solved and printed block by block (the solver and a printer)
#   facade        the installed library API (api/kinema/)
#   cli           the command
#   python        the Python module (a view beside the command)
#
# Configure runs kinema_check_stage_order over the tree (CMakeLists.txt); so does
# `cmake -DROOT=<tree> -P cmake/stage_order.cmake` (tests/CMakeLists.txt runs it on a tree
# with an upward include, which must fail).

# Path prefixes (from the project root) in stage order; a path takes the first prefix it
# starts with.
set(KINEMA_STAGES
  "base:engine/base/"
  "readers:readers/"
  "constraints:engine/constraints/"
  "front ends:loops/|linkages/|chains/"
  "symbolic:engine/symbolic/"
  "numeric:engine/numeric/"
  "model:engine/model."
  "analysis:engine/analysis/|engine/input_value."
  "problems:engine/problems/"
  "printers:engine/printers/"
  "run:engine/run/"
  "facade:api/"
  "cli:cli/"
  "python:python/")

# Upward includes that the reshaping of issue 34 has yet to remove: "file -> header".
# The list only shrinks: a new upward include fails configure, and so does an entry whose
# file no longer includes upward (remove it). Empty: every include runs downward. In
# script mode -DPENDING=<list> gives a list of its own (the check's own test, a small tree).
set(KINEMA_STAGE_ORDER_PENDING "")
if(CMAKE_SCRIPT_MODE_FILE AND DEFINED PENDING)
  set(KINEMA_STAGE_ORDER_PENDING "${PENDING}")
endif()

# Headers that solve (derive, differentiate, simplify, order the equations, or solve,
# compile or run a tape): a printer includes none of them. A printer formats what the
# model, the results and the analysis (engine/analysis/analysis.hpp) hold; what a view
# shows beyond the solved table is computed once, before any printer runs, by
# analyse_for_views. The data a printer shows from such a stage has a header of its own
# (engine/symbolic/dyad_derivation_types.hpp, engine/constraints/expansion.hpp).
set(KINEMA_PRINTER_FORBIDDEN_HEADERS
  "engine/symbolic/derivation.hpp"
  "engine/constraints/differentiate.hpp"
  "engine/symbolic/dyad_method.hpp"
  "engine/symbolic/solving_order.hpp"
  "engine/symbolic/trig_simplify.hpp"
  "engine/numeric/sweep.hpp"
  "engine/numeric/solver.hpp"
  "engine/numeric/circuit.hpp"
  "engine/numeric/closed_form.hpp"
  "engine/numeric/kinematics.hpp"
  "engine/numeric/workspace.hpp"
  "engine/numeric/batch_workspace.hpp"
  "engine/numeric/tape_ops.hpp"
  "engine/numeric/simd_math.hpp")

cmake_policy(SET CMP0057 NEW)  # if(IN_LIST), in script mode too

# The stage number of a path (from the root), or -1 for one outside every stage.
function(kinema_stage_of path out)
  set(index 0)
  foreach(stage IN LISTS KINEMA_STAGES)
    string(FIND "${stage}" ":" colon)
    math(EXPR start "${colon} + 1")
    string(SUBSTRING "${stage}" ${start} -1 prefixes)
    string(REPLACE "|" ";" prefixes "${prefixes}")
    foreach(prefix IN LISTS prefixes)
      string(FIND "${path}" "${prefix}" at)
      if(at EQUAL 0)
        set(${out} ${index} PARENT_SCOPE)
        return()
      endif()
    endforeach()
    math(EXPR index "${index} + 1")
  endforeach()
  set(${out} -1 PARENT_SCOPE)
endfunction()

function(kinema_stage_name index out)
  list(GET KINEMA_STAGES ${index} stage)
  string(FIND "${stage}" ":" colon)
  string(SUBSTRING "${stage}" 0 ${colon} name)
  set(${out} "${name}" PARENT_SCOPE)
endfunction()

# Fails (FATAL_ERROR) naming every include from a stage to a later one under root, but
# those in the pending list, and every include of a solving header by a printer. Includes are read as the tree writes them: "engine/..." from
# the root.
function(kinema_check_stage_order root)
  file(GLOB_RECURSE sources RELATIVE "${root}" "${root}/engine/*" "${root}/readers/*" "${root}/loops/*"
       "${root}/linkages/*" "${root}/chains/*" "${root}/cli/*" "${root}/api/*" "${root}/python/*")
  set(upward "")
  set(still_pending "")
  foreach(source IN LISTS sources)
    if(NOT source MATCHES "\\.(cpp|hpp|inc)$")
      continue()
    endif()
    kinema_stage_of("${source}" from)
    file(STRINGS "${root}/${source}" includes REGEX "^[ \t]*#[ \t]*include[ \t]*[<\"]")
    foreach(line IN LISTS includes)
      if(line MATCHES "#[ \t]*include[ \t]*[<\"](kinema/)?((engine|readers|loops|linkages|chains|cli|api|python)/[^>\"]+)[>\"]")
        set(header "${CMAKE_MATCH_2}")
      elseif(line MATCHES "#[ \t]*include[ \t]*<kinema/([^>/]+)>")
        # A program's spelling of the facade's headers: <kinema/kinema.hpp> is api/kinema/;
        # <kinema/error.hpp> is the base's error, copied beside it by the build.
        if(CMAKE_MATCH_1 STREQUAL "error.hpp")
          set(header "engine/base/error.hpp")
        else()
          set(header "api/kinema/${CMAKE_MATCH_1}")
        endif()
      else()
        continue()
      endif()
      if(source MATCHES "^engine/printers/" AND "${header}" IN_LIST KINEMA_PRINTER_FORBIDDEN_HEADERS)
        list(APPEND upward "${source} (printers) includes ${header}, a solving header: a printer only formats")
      endif()
      kinema_stage_of("${header}" to)
      if(from GREATER_EQUAL 0 AND to GREATER from AND "${source} -> ${header}" IN_LIST KINEMA_STAGE_ORDER_PENDING)
        list(APPEND still_pending "${source} -> ${header}")
      elseif(from GREATER_EQUAL 0 AND to GREATER from)
        kinema_stage_name(${from} from_name)
        kinema_stage_name(${to} to_name)
        list(APPEND upward "${source} (${from_name}) includes ${header} (${to_name})")
      endif()
    endforeach()
  endforeach()
  # A pending entry whose file no longer includes upward is done: the list only shrinks.
  foreach(entry IN LISTS KINEMA_STAGE_ORDER_PENDING)
    string(REGEX REPLACE " -> .*$" "" file "${entry}")
    if(EXISTS "${root}/${file}" AND NOT "${entry}" IN_LIST still_pending)
      list(APPEND upward "pending \"${entry}\" is no longer an upward include: remove it from KINEMA_STAGE_ORDER_PENDING")
    endif()
  endforeach()
  if(upward)
    list(JOIN upward "\n  " lines)
    message(FATAL_ERROR "an include from a stage to a later one, or of a solving header by a printer (the stages: cmake/stage_order.cmake):\n  ${lines}\n"
                        "Move what the earlier stage needs down to it (or to base), or the code up to the later stage.")
  endif()
endfunction()

if(CMAKE_SCRIPT_MODE_FILE AND DEFINED ROOT)
  kinema_check_stage_order("${ROOT}")
endif()
