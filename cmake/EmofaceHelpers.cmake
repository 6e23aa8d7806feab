# emoface CMake helpers: one function creates every library, one installs the package.
include(CMakePackageConfigHelpers)
include(GNUInstallDirs)

set_property(GLOBAL PROPERTY EMOFACE_LIBRARIES "")

# One warnings target (issue 18, docs/architecture.md#warnings): every library, app and test links it
# privately (through $<BUILD_INTERFACE:...>, so it never reaches the installed export set).
if(NOT TARGET emoface_warnings)
  add_library(emoface_warnings INTERFACE)
  target_compile_options(emoface_warnings INTERFACE
    $<$<CXX_COMPILER_ID:GNU,Clang>:-Wall -Wextra -Wpedantic -Wshadow -Wconversion -Wno-sign-conversion>)
endif()
set_property(GLOBAL PROPERTY EMOFACE_PACKAGE_DEPENDENCIES "")

# emoface_add_library(<lib> SOURCES ... [PUBLIC_DEPS ...] [PRIVATE_DEPS ...] [FIND_DEPENDENCIES ...])
# Creates the static target emoface_<lib> with alias emoface::<lib> and EXPORT_NAME <lib>.
# FIND_DEPENDENCIES lists the find_dependency() arguments the installed config needs for it,
# one string each (e.g. "nlohmann_json 3.10"); private deps of a static library count too.
function(emoface_add_library lib)
  cmake_parse_arguments(ARG "" "" "SOURCES;PUBLIC_DEPS;PRIVATE_DEPS;FIND_DEPENDENCIES" ${ARGN})
  if(NOT ARG_SOURCES)
    message(FATAL_ERROR "emoface_add_library(${lib}): SOURCES is required")
  endif()
  set(target emoface_${lib})
  add_library(${target} STATIC ${ARG_SOURCES})
  add_library(emoface::${lib} ALIAS ${target})
  set_target_properties(${target} PROPERTIES EXPORT_NAME ${lib} OUTPUT_NAME emoface_${lib})
  target_include_directories(${target}
    PUBLIC $<BUILD_INTERFACE:${CMAKE_CURRENT_SOURCE_DIR}/include>
           $<INSTALL_INTERFACE:${CMAKE_INSTALL_INCLUDEDIR}>
    PRIVATE ${CMAKE_CURRENT_SOURCE_DIR}/src)
  target_compile_features(${target} PUBLIC cxx_std_17)
  target_link_libraries(${target} PRIVATE $<BUILD_INTERFACE:emoface_warnings>)
  if(ARG_PUBLIC_DEPS)
    target_link_libraries(${target} PUBLIC ${ARG_PUBLIC_DEPS})
  endif()
  if(ARG_PRIVATE_DEPS)
    target_link_libraries(${target} PRIVATE ${ARG_PRIVATE_DEPS})
  endif()
  set_property(GLOBAL APPEND PROPERTY EMOFACE_LIBRARIES ${target})
  foreach(dep IN LISTS ARG_FIND_DEPENDENCIES)
    set_property(GLOBAL APPEND PROPERTY EMOFACE_PACKAGE_DEPENDENCIES "${dep}")
  endforeach()
  if(EMOFACE_INSTALL)
    install(DIRECTORY ${CMAKE_CURRENT_SOURCE_DIR}/include/ DESTINATION ${CMAKE_INSTALL_INCLUDEDIR})
  endif()
endfunction()

function(emoface_install_package)
  get_property(targets GLOBAL PROPERTY EMOFACE_LIBRARIES)
  get_property(deps GLOBAL PROPERTY EMOFACE_PACKAGE_DEPENDENCIES)
  list(REMOVE_DUPLICATES deps)
  set(EMOFACE_FIND_DEPENDENCIES "")
  foreach(dep IN LISTS deps)
    string(APPEND EMOFACE_FIND_DEPENDENCIES "find_dependency(${dep})\n")
  endforeach()
  install(TARGETS ${targets} EXPORT emofaceTargets
    ARCHIVE DESTINATION ${CMAKE_INSTALL_LIBDIR}
    LIBRARY DESTINATION ${CMAKE_INSTALL_LIBDIR}
    INCLUDES DESTINATION ${CMAKE_INSTALL_INCLUDEDIR})
  set(cfgdir ${CMAKE_INSTALL_LIBDIR}/cmake/emoface)
  install(EXPORT emofaceTargets NAMESPACE emoface:: DESTINATION ${cfgdir})
  configure_package_config_file(${PROJECT_SOURCE_DIR}/cmake/emofaceConfig.cmake.in
    ${PROJECT_BINARY_DIR}/emofaceConfig.cmake INSTALL_DESTINATION ${cfgdir})
  write_basic_package_version_file(${PROJECT_BINARY_DIR}/emofaceConfigVersion.cmake
    VERSION ${PROJECT_VERSION} COMPATIBILITY SameMajorVersion)
  install(FILES ${PROJECT_BINARY_DIR}/emofaceConfig.cmake ${PROJECT_BINARY_DIR}/emofaceConfigVersion.cmake
    DESTINATION ${cfgdir})
  install(DIRECTORY ${PROJECT_SOURCE_DIR}/data/ DESTINATION ${CMAKE_INSTALL_DATADIR}/emoface)
endfunction()

# emoface_add_app(<tool> SOURCES ... DEPS ...): a thin CLI linked with the shared CLI glue.
function(emoface_add_app tool)
  cmake_parse_arguments(ARG "" "" "SOURCES;DEPS" ${ARGN})
  add_executable(${tool} ${ARG_SOURCES})
  target_link_libraries(${tool} PRIVATE emoface_cli ${ARG_DEPS})
  target_link_libraries(${tool} PRIVATE emoface_warnings)
  if(EMOFACE_INSTALL)
    install(TARGETS ${tool} RUNTIME DESTINATION ${CMAKE_INSTALL_BINDIR})
  endif()
endfunction()
