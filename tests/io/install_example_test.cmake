# cmake -P script: stage an install of BUILD_DIR, then configure, build and run EXAMPLE_DIR
# against it: the core example, then the pipeline one (Mapper over PCDs the installed `vantage
# scan` wrote), then the installed `vantage plan`, which must draw its picture with the installed
# plot scripts. Fails with the step's output when a step fails.
foreach(var BUILD_DIR EXAMPLE_DIR WORK_DIR CXX_COMPILER GENERATOR)
  if(NOT DEFINED ${var})
    message(FATAL_ERROR "install_example_test: ${var} is not set")
  endif()
endforeach()

function(step name)
  execute_process(COMMAND ${ARGN} WORKING_DIRECTORY ${WORK_DIR} RESULT_VARIABLE rc
                  OUTPUT_VARIABLE out ERROR_VARIABLE err)
  if(NOT rc EQUAL 0)
    message(FATAL_ERROR "install_example_test: ${name} failed (${rc})\n${out}\n${err}")
  endif()
  set(step_output "${out}" PARENT_SCOPE)
endfunction()

set(prefix ${WORK_DIR}/prefix)
file(REMOVE_RECURSE ${WORK_DIR})
file(MAKE_DIRECTORY ${WORK_DIR})
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

# The pipeline: the installed binary and scripts, two clouds, Mapper, and plan's picture.
set(vantage ${prefix}/bin/vantage)
foreach(file ${vantage} ${prefix}/share/vantage/scripts/plot_run.py
             ${prefix}/share/vantage/scripts/plot_top_view.py)
  if(NOT EXISTS ${file})
    message(FATAL_ERROR "install_example_test: ${file} is not installed")
  endif()
endforeach()
# NOTE: the built binary falls back to the source tree's scripts, which exist here too; a marker
# that only the installed copy writes shows which one drew the picture.
file(APPEND ${prefix}/share/vantage/scripts/plot_run.py
     "\nopen(os.path.join(sys.argv[1], 'drawn-by-installed-scripts'), 'w').close()\n")
step("make-data.sh" ${EXAMPLE_DIR}/own-scans/make-data.sh ${WORK_DIR}/data ${vantage})
step("map_scans" ${WORK_DIR}/build/map_scans ${WORK_DIR}/data)
message(STATUS "${step_output}")
if(NOT step_output MATCHES "cloud 2: [0-9]+ points" OR
   NOT step_output MATCHES "next best view [0-9]+ of 30 at" OR NOT EXISTS ${WORK_DIR}/map.ot)
  message(FATAL_ERROR "install_example_test: map_scans did not map and plan:\n${step_output}")
endif()
step("vantage plan" ${CMAKE_COMMAND} -E env --unset=VANTAGE_SCRIPTS_DIR
     ${vantage} plan ${WORK_DIR}/data --out ${WORK_DIR}/plan --threads 2)
message(STATUS "${step_output}")
foreach(file plan.json map.ot map.bt map.ply map.png drawn-by-installed-scripts)
  if(NOT EXISTS ${WORK_DIR}/plan/${file})
    message(FATAL_ERROR "install_example_test: the installed vantage plan wrote no ${file}")
  endif()
endforeach()
