# Install and export: `cmake --install <build> [--prefix P]` installs the headers (vantage/**.hpp,
# layout preserved), the libraries, a CMake package, the `vantage` binary and its plot scripts
# (share/vantage/scripts, where the installed binary looks for them), so that a user project writes
#   find_package(vantage REQUIRED)
#   target_link_libraries(app PRIVATE vantage::vantage)
# vantage::vantage links the core and every installed edge module; vantage::core, vantage::io, ...
# are there too. Included once, at the end of the top-level CMakeLists.txt, when every target
# exists.
include(GNUInstallDirs)
include(CMakePackageConfigHelpers)

set(VANTAGE_INSTALL_CMAKEDIR ${CMAKE_INSTALL_LIBDIR}/cmake/vantage)

# Package that provides a third-party link item of an installed module, for find_dependency in
# vantageConfig.cmake. Empty when the item needs no package (a system library or a flag).
function(_vantage_package_of item out)
  set(package "")
  if(item MATCHES "^Eigen3::")
    set(package "Eigen3 3.3 NO_MODULE")
  elseif(item MATCHES "^TBB::")
    set(package "TBB")
  elseif(item MATCHES "^(octomap|octomath)(-static)?$")
    set(package "octomap")
  elseif(item MATCHES "^yaml-cpp(::yaml-cpp)?$")
    set(package "yaml-cpp")
  elseif(item MATCHES "^PNG::")
    set(package "PNG")
  elseif(item MATCHES "^ZLIB::")
    set(package "ZLIB")
  elseif(item MATCHES "^pcl_" OR item MATCHES "^PCL::")
    set(package "PCL")
  elseif(item MATCHES "^embree")
    set(package "embree 3")
  elseif(item MATCHES "^assimp")
    set(package "assimp")
  elseif(item MATCHES "^fmt::")
    set(package "fmt")
  elseif(item MATCHES "^spdlog::")
    set(package "spdlog")
  elseif(item MATCHES "^nlohmann_json::")
    set(package "nlohmann_json")
  elseif(item MATCHES "^nanoflann::")
    set(package "nanoflann")
  elseif(item MATCHES "^Threads::")
    set(package "Threads")
  elseif(item MATCHES "^OpenMP::")
    set(package "OpenMP")
  elseif(item MATCHES "^-" OR item MATCHES "^(m|dl|pthread|rt|stdc\\+\\+fs)$" OR IS_ABSOLUTE "${item}")
    set(package "")
  else()
    set(package "?")
  endif()
  set(${out} "${package}" PARENT_SCOPE)
endfunction()

# The link items of a target, with $<LINK_ONLY:x> unwrapped and build-only items dropped.
function(_vantage_link_items target out)
  get_target_property(direct ${target} LINK_LIBRARIES)
  get_target_property(interface ${target} INTERFACE_LINK_LIBRARIES)
  set(items "")
  foreach(item IN LISTS direct interface)
    if(NOT item OR item MATCHES "-NOTFOUND$" OR item MATCHES "^\\$<BUILD_INTERFACE:")
      continue()
    endif()
    string(REGEX REPLACE "^\\$<LINK_ONLY:(.*)>$" "\\1" item "${item}")
    if(item MATCHES "\\$<")
      continue()
    endif()
    list(APPEND items "${item}")
  endforeach()
  list(REMOVE_DUPLICATES items)
  set(${out} "${items}" PARENT_SCOPE)
endfunction()

# Modules to install: the core, and each edge module this build has whose link items are all
# vantage modules or known packages. A module that links something else is left out with a
# warning, rather than breaking the export for everyone.
set(_vantage_modules core)
foreach(edge sim perception io experiment)
  if(TARGET vantage_${edge})
    list(APPEND _vantage_modules ${edge})
  endif()
endforeach()

# NOTE: perception links vantage_pcl, an IMPORTED target of its own (PCL's headers and the few PCL
# libraries it calls, without the VTK and Qt that PCL's component targets drag in). An imported
# target is not exported: the exported link interface names it, and vantageConfig.cmake recreates
# it from the consumer's find_dependency(PCL COMPONENTS ...), the components read off its
# libraries (libpcl_<component>.so).
set(_vantage_recreated "")
function(_vantage_pcl_components_of target out)
  get_target_property(libraries ${target} INTERFACE_LINK_LIBRARIES)
  set(components "")
  foreach(library IN LISTS libraries)
    get_filename_component(name "${library}" NAME)
    if(name MATCHES "^(lib)?pcl_([a-z_0-9]+)(\\.|$)")
      list(APPEND components ${CMAKE_MATCH_2})
    else()
      message(FATAL_ERROR "VantageInstall: ${target} links '${library}', not a PCL library")
    endif()
  endforeach()
  set(${out} "${components}" PARENT_SCOPE)
endfunction()

set(_vantage_installed "")
set(_vantage_packages "")
set(_vantage_pcl_components "")
foreach(module IN LISTS _vantage_modules)
  _vantage_link_items(vantage_${module} items)
  set(ok TRUE)
  set(packages "")
  foreach(item IN LISTS items)
    if(item STREQUAL "vantage_pcl")
      _vantage_pcl_components_of(vantage_pcl components)
      list(APPEND packages PCL)
      list(APPEND _vantage_pcl_components ${components})
      list(APPEND _vantage_recreated vantage_pcl)
      continue()
    endif()
    if(item MATCHES "^vantage(::|_)(.+)$")
      list(APPEND _vantage_needs_${module} ${CMAKE_MATCH_2})
      continue()
    endif()
    _vantage_package_of("${item}" package)
    if(package STREQUAL "?")
      message(WARNING "VantageInstall: vantage_${module} links '${item}', which no package in "
                      "cmake/VantageInstall.cmake provides; vantage::${module} is not installed")
      set(ok FALSE)
    elseif(package)
      list(APPEND packages "${package}")
      if(item MATCHES "^pcl_(.+)$")
        list(APPEND _vantage_pcl_components ${CMAKE_MATCH_1})
      endif()
    endif()
  endforeach()
  if(ok)
    list(APPEND _vantage_installed ${module})
    list(APPEND _vantage_packages ${packages})
  endif()
endforeach()
# A module needs every vantage module it links; drop those whose needs are not installed.
foreach(module IN LISTS _vantage_installed)
  foreach(need IN LISTS _vantage_needs_${module})
    if(NOT need IN_LIST _vantage_installed)
      message(WARNING "VantageInstall: vantage_${module} needs vantage_${need}, which is not "
                      "installed; vantage::${module} is not installed")
      list(REMOVE_ITEM _vantage_installed ${module})
    endif()
  endforeach()
endforeach()
list(REMOVE_DUPLICATES _vantage_packages)

# vantage::vantage: everything installed, and the C++ standard the headers need.
add_library(vantage_all INTERFACE)
add_library(vantage::vantage ALIAS vantage_all)
set_target_properties(vantage_all PROPERTIES EXPORT_NAME vantage)
target_compile_features(vantage_all INTERFACE cxx_std_20)
set(_vantage_targets "")
foreach(module IN LISTS _vantage_installed)
  list(APPEND _vantage_targets vantage_${module})
  target_compile_features(vantage_${module} INTERFACE cxx_std_20)
endforeach()
target_link_libraries(vantage_all INTERFACE ${_vantage_targets})

install(TARGETS ${_vantage_targets} vantage_all
        EXPORT vantageTargets
        ARCHIVE DESTINATION ${CMAKE_INSTALL_LIBDIR}
        LIBRARY DESTINATION ${CMAKE_INSTALL_LIBDIR}
        RUNTIME DESTINATION ${CMAKE_INSTALL_BINDIR}
        INCLUDES DESTINATION ${CMAKE_INSTALL_INCLUDEDIR})

# Headers of the core's folders and of each installed edge, layout preserved. Headers under a
# detail/ folder are private to a module's .cpp files (they may include third-party headers) and
# stay out.
set(_vantage_header_dirs map gain views planner util)
foreach(module IN LISTS _vantage_installed)
  if(NOT module STREQUAL "core")
    list(APPEND _vantage_header_dirs ${module})
  endif()
endforeach()
foreach(dir IN LISTS _vantage_header_dirs)
  install(DIRECTORY ${PROJECT_SOURCE_DIR}/vantage/${dir}/
          DESTINATION ${CMAKE_INSTALL_INCLUDEDIR}/vantage/${dir}
          FILES_MATCHING PATTERN "*.hpp"
          PATTERN "detail" EXCLUDE)
endforeach()

install(EXPORT vantageTargets NAMESPACE vantage:: DESTINATION ${VANTAGE_INSTALL_CMAKEDIR})

# find_dependency lines for the config file.
set(VANTAGE_FIND_DEPENDENCIES "")
set(VANTAGE_NEEDS_C OFF)
foreach(package IN LISTS _vantage_packages)
  if(package STREQUAL "PCL")
    # Only the components the modules link: all of PCL would pull in VTK and Qt.
    set(VANTAGE_NEEDS_C ON)
    if(_vantage_pcl_components)
      list(REMOVE_DUPLICATES _vantage_pcl_components)
      list(JOIN _vantage_pcl_components " " components)
      set(package "PCL COMPONENTS ${components}")
    endif()
  endif()
  string(APPEND VANTAGE_FIND_DEPENDENCIES "find_dependency(${package})\n")
endforeach()
set(VANTAGE_INSTALLED_MODULES "${_vantage_installed}")

# The recreated vantage_pcl: the same PCL libraries, as the consumer's find_package(PCL) found them.
set(VANTAGE_RECREATE_TARGETS "")
if("vantage_pcl" IN_LIST _vantage_recreated)
  set(libraries "")
  foreach(component IN LISTS _vantage_pcl_components)
    string(TOUPPER ${component} upper)
    list(APPEND libraries "\${PCL_${upper}_LIBRARY}")
  endforeach()
  list(JOIN libraries ";" libraries)
  string(APPEND VANTAGE_RECREATE_TARGETS
         "if(NOT TARGET vantage_pcl)\n"
         "  add_library(vantage_pcl INTERFACE IMPORTED)\n"
         "  set_target_properties(vantage_pcl PROPERTIES INTERFACE_LINK_LIBRARIES \"${libraries}\")\n"
         "endif()\n")
endif()

configure_package_config_file(${PROJECT_SOURCE_DIR}/cmake/vantageConfig.cmake.in
                              ${PROJECT_BINARY_DIR}/vantageConfig.cmake
                              INSTALL_DESTINATION ${VANTAGE_INSTALL_CMAKEDIR})
# NOTE: 0.x: a minor version may change the API.
write_basic_package_version_file(${PROJECT_BINARY_DIR}/vantageConfigVersion.cmake
                                 VERSION ${PROJECT_VERSION} COMPATIBILITY SameMinorVersion)
install(FILES ${PROJECT_BINARY_DIR}/vantageConfig.cmake
              ${PROJECT_BINARY_DIR}/vantageConfigVersion.cmake
        DESTINATION ${VANTAGE_INSTALL_CMAKEDIR})
# The command-line tool and the plot scripts it runs. The binary finds them at
# VANTAGE_INSTALLED_SCRIPTS_DIR, relative to its own folder (see apps/vantage/shell.cpp).
if(TARGET vantage)
  install(TARGETS vantage RUNTIME DESTINATION ${CMAKE_INSTALL_BINDIR})
endif()
file(GLOB _vantage_scripts ${PROJECT_SOURCE_DIR}/scripts/plot_*.py)
install(PROGRAMS ${_vantage_scripts} DESTINATION ${CMAKE_INSTALL_DATADIR}/vantage/scripts)

message(STATUS "Vantage install: modules ${_vantage_installed}; packages ${_vantage_packages}")
