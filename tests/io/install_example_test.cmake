# cmake -P script: stage an install of BUILD_DIR, then configure, build and run EXAMPLE_DIR
# against it. Fails with the step's output when a step fails.
foreach(var BUILD_DIR EXAMPLE_DIR WORK_DIR CXX_COMPILER GENERATOR)
  if(NOT DEFINED ${var})
    message(FATAL_ERROR "install_example_test: ${var} is not set")
  endif()
endforeach()

function(step name)
  execute_process(COMMAND ${ARGN} RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
  if(NOT rc EQUAL 0)
    message(FATAL_ERROR "install_example_test: ${name} failed (${rc})\n${out}\n${err}")
  endif()
  set(step_output "${out}" PARENT_SCOPE)
endfunction()

set(prefix ${WORK_DIR}/prefix)
file(REMOVE_RECURSE ${WORK_DIR})
step("cmake --install" ${CMAKE_COMMAND} --install ${BUILD_DIR} --prefix ${prefix})

# No third-party header may leak into an installed Vantage header.
file(GLOB_RECURSE headers ${prefix}/include/vantage/*.hpp)
list(LENGTH headers header_count)
if(header_count EQUAL 0)
  message(FATAL_ERROR "install_example_test: no headers installed under ${prefix}/include/vantage")
endif()
foreach(header IN LISTS headers)
  file(STRINGS ${header} includes REGEX "^#include")
  foreach(line IN LISTS includes)
    if(line MATCHES "[<\"](octomap|yaml-cpp|pcl|embree3|assimp|fmt|spdlog)/")
      message(FATAL_ERROR "install_example_test: ${header} leaks a third-party header: ${line}")
    endif()
    # Every Vantage header an installed header includes is installed too.
    if(line MATCHES "[<\"](vantage/[^>\"]+)[>\"]" AND NOT EXISTS ${prefix}/include/${CMAKE_MATCH_1})
      message(FATAL_ERROR "install_example_test: ${header} includes ${CMAKE_MATCH_1}, "
                          "which is not installed")
    endif()
  endforeach()
endforeach()

set(config_args -G ${GENERATOR} -DCMAKE_BUILD_TYPE=Release -DCMAKE_CXX_COMPILER=${CXX_COMPILER}
                -Dvantage_DIR=${prefix}/lib/cmake/vantage -DCMAKE_PREFIX_PATH=${prefix}
                -DCMAKE_FIND_USE_PACKAGE_REGISTRY=OFF)
if(C_COMPILER)
  list(APPEND config_args -DCMAKE_C_COMPILER=${C_COMPILER})
endif()
# The config lives in lib/ or lib/<multiarch>/ depending on GNUInstallDirs; find it.
file(GLOB_RECURSE configs ${prefix}/vantageConfig.cmake)
if(NOT configs)
  message(FATAL_ERROR "install_example_test: no vantageConfig.cmake under ${prefix}")
endif()
list(GET configs 0 config)
get_filename_component(config_dir ${config} DIRECTORY)
list(TRANSFORM config_args REPLACE "^-Dvantage_DIR=.*" "-Dvantage_DIR=${config_dir}")

step("configure example" ${CMAKE_COMMAND} -S ${EXAMPLE_DIR} -B ${WORK_DIR}/build ${config_args})
step("build example" ${CMAKE_COMMAND} --build ${WORK_DIR}/build)
execute_process(COMMAND ${WORK_DIR}/build/plan_next_view WORKING_DIRECTORY ${WORK_DIR}
                RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
message(STATUS "${out}")
if(NOT rc EQUAL 0 OR NOT out MATCHES "best view [0-9]+ of 30 at" OR NOT EXISTS ${WORK_DIR}/map.bt)
  message(FATAL_ERROR "install_example_test: the example failed (${rc}):\n${out}\n${err}")
endif()
