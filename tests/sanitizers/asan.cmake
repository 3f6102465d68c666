# Included right after project() by the sanitizer builds (CMAKE_PROJECT_jade_INCLUDE: the `asan`
# preset and third_party/build.sh's ASan subset): links keep_loaded.c (a no-op dlclose; see there
# why) into every executable, so that LeakSanitizer can scan and name the Vulkan drivers and
# layers at exit.
#
# Only executables: the definition must be in the program to interpose libc's dlclose, and a
# library that linked it would carry it in its exported link interface (install(EXPORT) refuses
# a target outside the export set). The executables are known only once every directory has been
# read, hence the call deferred to the end of the top-level directory.
# Also included (as CMAKE_PROJECT_INCLUDE) by the consumer projects that tests/consumer builds
# against a sanitized install, which may enable only C++.
if(NOT CMAKE_C_COMPILER_LOADED)
  enable_language(C)
endif()
add_library(jade_asan_keep_loaded OBJECT ${CMAKE_CURRENT_LIST_DIR}/keep_loaded.c)

function(jade_asan_link_keep_loaded dir)
  get_property(targets DIRECTORY ${dir} PROPERTY BUILDSYSTEM_TARGETS)
  foreach(t IN LISTS targets)
    get_target_property(type ${t} TYPE)
    get_target_property(imported ${t} IMPORTED)
    if(type STREQUAL "EXECUTABLE" AND NOT imported)
      target_link_libraries(${t} PRIVATE jade_asan_keep_loaded)
    endif()
  endforeach()
  get_property(subdirs DIRECTORY ${dir} PROPERTY SUBDIRECTORIES)
  foreach(sub IN LISTS subdirs)
    jade_asan_link_keep_loaded(${sub})
  endforeach()
endfunction()

cmake_language(DEFER DIRECTORY ${CMAKE_SOURCE_DIR} CALL jade_asan_link_keep_loaded ${CMAKE_SOURCE_DIR})
