# Shared settings for Vantage's own targets. Third-party headers come in as SYSTEM includes, so
# -Werror applies to our code only (GCC 12 warns falsely in Eigen code that PCL instantiates).

function(vantage_target_defaults target)
  target_compile_options(${target} PRIVATE -Wall -Wextra -Wpedantic -Wshadow -Wconversion
                                           -Wno-sign-conversion)
  if(VANTAGE_WERROR)
    target_compile_options(${target} PRIVATE -Werror)
  endif()
  if(VANTAGE_FUZZ)
    # libFuzzer's coverage, and undefined behaviour that stops the run, so the fuzzer sees it.
    target_compile_options(${target} PUBLIC -fsanitize=fuzzer-no-link,address,undefined
                                            -fno-sanitize-recover=undefined -fno-omit-frame-pointer)
    target_link_options(${target} PUBLIC -fsanitize=address,undefined)
  elseif(VANTAGE_SANITIZE)
    target_compile_options(${target} PUBLIC -fsanitize=address,undefined -fno-omit-frame-pointer)
    target_link_options(${target} PUBLIC -fsanitize=address,undefined)
  elseif(VANTAGE_TSAN)
    target_compile_options(${target} PUBLIC -fsanitize=thread -fno-omit-frame-pointer)
    target_link_options(${target} PUBLIC -fsanitize=thread)
  endif()
  if(VANTAGE_FUZZ OR VANTAGE_SANITIZE)
    # NOTE: under ASan, Eigen stops trusting malloc's 16-byte alignment and pads its own
    # allocations. Eigen's inline allocator in our binary then interposes on PCL's (built
    # without ASan), and PCL frees with plain free() what our copy allocated padded: a bad free
    # in RANSAC. Debian's PCL trusts malloc, so our code must too.
    target_compile_definitions(${target} PUBLIC EIGEN_MALLOC_ALREADY_ALIGNED=1)
  endif()
endfunction()

# vantage_add_module(NAME <name> SOURCES ... [PUBLIC_DEPS ...] [PRIVATE_DEPS ...])
# One library per stage of the data's way; headers live beside the sources.
function(vantage_add_module)
  cmake_parse_arguments(ARG "" "NAME" "SOURCES;PUBLIC_DEPS;PRIVATE_DEPS" ${ARGN})
  set(target vantage_${ARG_NAME})
  add_library(${target} ${ARG_SOURCES})
  add_library(vantage::${ARG_NAME} ALIAS ${target})
  target_include_directories(${target} PUBLIC $<BUILD_INTERFACE:${PROJECT_SOURCE_DIR}>
                                              $<INSTALL_INTERFACE:include>)
  target_link_libraries(${target} PUBLIC ${ARG_PUBLIC_DEPS} PRIVATE ${ARG_PRIVATE_DEPS})
  set_target_properties(${target} PROPERTIES POSITION_INDEPENDENT_CODE ON
                                             EXPORT_NAME ${ARG_NAME})
  vantage_target_defaults(${target})
endfunction()

# vantage_add_test(NAME <name> SOURCES ... DEPS ...)
function(vantage_add_test)
  cmake_parse_arguments(ARG "" "NAME" "SOURCES;DEPS;LABELS" ${ARGN})
  add_executable(${ARG_NAME} ${ARG_SOURCES})
  target_link_libraries(${ARG_NAME} PRIVATE ${ARG_DEPS} GTest::gtest_main)
  vantage_target_defaults(${ARG_NAME})
  gtest_discover_tests(${ARG_NAME} WORKING_DIRECTORY ${PROJECT_SOURCE_DIR}
                       PROPERTIES ENVIRONMENT "VANTAGE_SOURCE_DIR=${PROJECT_SOURCE_DIR}"
                                  LABELS "${ARG_LABELS}"
                       DISCOVERY_TIMEOUT 60)
endfunction()
