# Every output of one sample, compared byte for byte with the copy stored in tests/golden/
# (or, with -DUPDATE=ON, stored anew). The stored outputs were taken before the middle of the
# engine was reshaped (issue 34), so a reshaping shows that no view changed; a fix that is meant
# to change an output stores it again in the same commit (`cmake --build build --target
# update_golden_outputs`), and the diff shows what changed.
#
#   cmake -DKINEMA=build/kinema -DSAMPLES_DIR=samples -DSAMPLE=four_bar -DGOLDEN_DIR=tests/golden
#         -DWORK_DIR=/tmp/out [-DUPDATE=ON] -P tests/golden/outputs.cmake
#
# Runs in the samples folder with the file's bare name, as a user in that folder would, so
# that no output names the machine's paths. A command the sample refuses (a dyad method on a
# vector-loop file) has no stored output: the refusal is then checked to stay a refusal.
cmake_minimum_required(VERSION 3.16)
foreach(required KINEMA SAMPLES_DIR SAMPLE GOLDEN_DIR WORK_DIR)
  if(NOT DEFINED ${required})
    message(FATAL_ERROR "outputs.cmake: -D${required}=... is needed")
  endif()
endforeach()

set(file "${SAMPLE}.toml")
# name|argument|argument... ('|' between them: a ';' would split the list); the output is the command's stdout, or the -o file of codegen.
set(commands
  "eval.txt|eval|${file}"
  "eval.csv|eval|${file}|--format|csv"
  "eval.json|eval|${file}|--format|json"
  "eval.npy|eval|${file}|--format|npy"
  "latex.tex|latex|${file}"
  "codegen.hpp|codegen|${file}|-o|${WORK_DIR}/${SAMPLE}.hpp"
  "loops.toml|loops|${file}")
foreach(method loops relative-velocity joint-coordinates)
  list(APPEND commands
    "derive.${method}.txt|derive|${file}|--method|${method}"
    "derive.${method}.tex|derive|${file}|--method|${method}|--format|latex"
    "latex.${method}.tex|latex|${file}|--method|${method}")
endforeach()

file(MAKE_DIRECTORY "${WORK_DIR}" "${GOLDEN_DIR}/${SAMPLE}")
set(changed "")
foreach(entry IN LISTS commands)
  string(FIND "${entry}" "|" bar)
  string(SUBSTRING "${entry}" 0 ${bar} name)
  math(EXPR after "${bar} + 1")
  string(SUBSTRING "${entry}" ${after} -1 arguments)
  string(REPLACE "|" ";" arguments "${arguments}")
  set(output "${WORK_DIR}/${SAMPLE}.${name}")
  file(REMOVE "${output}" "${WORK_DIR}/${SAMPLE}.hpp")
  execute_process(COMMAND "${KINEMA}" ${arguments}
                  WORKING_DIRECTORY "${SAMPLES_DIR}"
                  OUTPUT_FILE "${output}" ERROR_VARIABLE error RESULT_VARIABLE status)
  if(name STREQUAL "codegen.hpp" AND status EQUAL 0)
    file(RENAME "${WORK_DIR}/${SAMPLE}.hpp" "${output}")
  endif()
  set(stored "${GOLDEN_DIR}/${SAMPLE}/${name}")
  if(NOT status EQUAL 0 AND NOT status EQUAL 2)
    list(APPEND changed "${name} (exit ${status}: ${error})")
  elseif(UPDATE)
    if(status EQUAL 0)
      file(COPY_FILE "${output}" "${stored}" ONLY_IF_DIFFERENT)
    else()
      file(REMOVE "${stored}")
    endif()
  elseif(status EQUAL 0 AND NOT EXISTS "${stored}")
    list(APPEND changed "${name} (now written, none stored)")
  elseif(status EQUAL 2 AND EXISTS "${stored}")
    list(APPEND changed "${name} (now refused: ${error})")
  elseif(status EQUAL 0)
    execute_process(COMMAND "${CMAKE_COMMAND}" -E compare_files "${stored}" "${output}" RESULT_VARIABLE differs)
    if(NOT differs EQUAL 0)
      list(APPEND changed "${name} (diff ${stored} ${output})")
    endif()
  endif()
endforeach()

if(changed)
  list(JOIN changed "\n  " lines)
  message(FATAL_ERROR "${SAMPLE}: outputs differ from tests/golden/${SAMPLE}/:\n  ${lines}\n"
                      "If the change is meant (a fix), store it with the fix: cmake --build <build> --target update_golden_outputs")
endif()
