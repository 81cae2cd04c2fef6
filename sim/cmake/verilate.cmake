# SPDX-License-Identifier: MIT
# verilate(TARGET PREFIX p TOP_MODULE m SOURCES ... [INCLUDE_DIRS ...]
#          [VERILATOR_ARGS ...] [OPT_FAST ...] [OPT_SLOW ...] [OPT_GLOBAL ...])
#
# Adds the Verilated C++ model of an RTL design to TARGET, with the
# arguments of Verilator's own CMake function of that name, which the PyPI
# wheel does not ship. Built on the build description Verilator writes
# itself (`verilator --make json`: the generated files by kind, the
# runtime files, the options, the inputs it read):
#   - Verilator runs at configure time, when its command line changed or
#     an input it read is newer than the description (CMake configures
#     again by itself when one of those inputs changes), and at build time
#     when a generated file is missing or older than an input;
#   - the fast classes compile with OPT_FAST, the slow ones with OPT_SLOW,
#     the runtime (verilated.cpp, ...) with OPT_GLOBAL, after the target's
#     own flags (so these win);
#   - the VM_* macros of the model come from the description's options.
# Needs VERILATOR_ROOT (a Verilator with `--make json`, version 1).

function(verilate target)
  cmake_parse_arguments(V "" "PREFIX;TOP_MODULE" "SOURCES;INCLUDE_DIRS;VERILATOR_ARGS;OPT_FAST;OPT_SLOW;OPT_GLOBAL"
                        ${ARGN})
  if(NOT V_PREFIX OR NOT V_TOP_MODULE OR NOT V_SOURCES)
    message(FATAL_ERROR "verilate(${target}): PREFIX, TOP_MODULE and SOURCES are required")
  endif()
  find_program(VERILATOR_BIN verilator_bin PATHS ${VERILATOR_ROOT}/bin NO_DEFAULT_PATH REQUIRED)
  set(vdir ${CMAKE_CURRENT_BINARY_DIR}/${V_PREFIX}.dir)
  set(cmd ${CMAKE_COMMAND} -E env VERILATOR_ROOT=${VERILATOR_ROOT} ${VERILATOR_BIN} --cc --make json
          --prefix ${V_PREFIX} --top-module ${V_TOP_MODULE} --Mdir ${vdir})
  foreach(dir ${V_INCLUDE_DIRS})
    list(APPEND cmd -y ${dir})
  endforeach()
  list(APPEND cmd ${V_VERILATOR_ARGS} ${V_SOURCES})
  set(manifest ${vdir}/${V_PREFIX}.json)
  set(command_file ${vdir}/verilator_command.txt)

  set(run FALSE)
  if(NOT EXISTS ${manifest} OR NOT EXISTS ${command_file})
    set(run TRUE)
  else()
    file(READ ${command_file} previous)
    if(NOT previous STREQUAL "${cmd}")
      set(run TRUE)
    else()
      _verilate_list(inputs ${manifest} deps)
      foreach(f ${inputs})
        if(NOT EXISTS ${f} OR ${f} IS_NEWER_THAN ${manifest})
          set(run TRUE)
        endif()
      endforeach()
    endif()
  endif()
  if(run)
    message(STATUS "Verilating ${V_TOP_MODULE} (${V_PREFIX})")
    file(MAKE_DIRECTORY ${vdir})
    execute_process(COMMAND ${cmd} RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE out)
    if(rc)
      list(JOIN cmd " " shown)
      message(FATAL_ERROR "Verilator failed (status ${rc}):\n${shown}\n${out}")
    endif()
    file(WRITE ${command_file} "${cmd}")
  endif()

  file(READ ${manifest} json)
  string(JSON version GET "${json}" version)
  if(NOT version EQUAL 1)
    message(FATAL_ERROR "verilate(${target}): ${manifest} is version ${version} of Verilator's build description; "
            "sim/cmake/verilate.cmake reads version 1")
  endif()
  foreach(kind global classes_fast classes_slow support_fast support_slow deps)
    _verilate_list(${kind} ${manifest} ${kind})
  endforeach()
  set(defs VERILATOR=1)
  foreach(opt coverage system_c use_timing trace trace_fst trace_vcd trace_saif)
    string(JSON value GET "${json}" options ${opt})
    string(TOUPPER ${opt} name)
    string(REPLACE "SYSTEM_C" "SC" name ${name})
    string(REPLACE "USE_TIMING" "TIMING" name ${name})
    list(APPEND defs VM_${name}=$<BOOL:${value}>)
    if(value AND opt MATCHES "system_c|use_timing")
      message(FATAL_ERROR "verilate(${target}): ${opt} is not supported here")
    endif()
  endforeach()

  set(generated ${classes_fast} ${classes_slow} ${support_fast} ${support_slow})
  add_custom_command(OUTPUT ${generated} COMMAND ${cmd} DEPENDS ${deps}
                     COMMENT "Verilating ${V_TOP_MODULE}" VERBATIM)
  set_property(DIRECTORY APPEND PROPERTY CMAKE_CONFIGURE_DEPENDS ${deps})
  target_sources(${target} PRIVATE ${generated} ${global})
  set_source_files_properties(${classes_fast} ${support_fast} PROPERTIES COMPILE_OPTIONS "${V_OPT_FAST}")
  set_source_files_properties(${classes_slow} ${support_slow} PROPERTIES COMPILE_OPTIONS "${V_OPT_SLOW}")
  set_source_files_properties(${global} PROPERTIES COMPILE_OPTIONS "${V_OPT_GLOBAL}")
  target_include_directories(${target} PRIVATE ${vdir} ${VERILATOR_ROOT}/include ${VERILATOR_ROOT}/include/vltstd)
  target_compile_definitions(${target} PRIVATE ${defs})
  find_package(Threads REQUIRED)
  target_link_libraries(${target} PRIVATE Threads::Threads)
endfunction()

# out = the list sources.<kind> of Verilator's build description `manifest`.
function(_verilate_list out manifest kind)
  file(READ ${manifest} json)
  set(items)
  string(JSON n ERROR_VARIABLE err LENGTH "${json}" sources ${kind})
  if(err STREQUAL "NOTFOUND" AND n GREATER 0)
    math(EXPR last "${n} - 1")
    foreach(i RANGE ${last})
      string(JSON f GET "${json}" sources ${kind} ${i})
      list(APPEND items ${f})
    endforeach()
  endif()
  set(${out} ${items} PARENT_SCOPE)
endfunction()
