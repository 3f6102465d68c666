# Included right after project() by the `asan` preset (CMAKE_PROJECT_jade_INCLUDE): links
# keep_loaded.c (a no-op dlclose; see there why) into every target defined after this point, so
# that LeakSanitizer can scan and name the Vulkan drivers and layers at exit.
add_library(jade_asan_keep_loaded OBJECT ${CMAKE_CURRENT_LIST_DIR}/keep_loaded.c)
link_libraries(jade_asan_keep_loaded)
