# Install rules: headers, the static libraries and a relocatable CMake package.
#   find_package(jade 0.1 REQUIRED)               -> jade::jade (core: Vulkan, GLM)
#   find_package(jade 0.1 REQUIRED COMPONENTS io)  -> also jade::io (tinygltf, tinyobjloader, OIIO)
# Static libraries carry their private dependencies as link-only: libjade_shaders.a (the
# embedded SPIR-V) is installed and exported with the core, and jadeConfig.cmake finds the
# packages the libraries link (Vulkan, GLM, Threads; for io also TinyGLTF, tinyobjloader and
# OpenImageIO through pkg-config).
include(GNUInstallDirs)
include(CMakePackageConfigHelpers)

set(JADE_CMAKE_DIR ${CMAKE_INSTALL_LIBDIR}/cmake/jade)

set_target_properties(jade PROPERTIES EXPORT_NAME jade)
set_target_properties(jade_io PROPERTIES EXPORT_NAME io)
set_target_properties(jade_shaders PROPERTIES EXPORT_NAME shaders)

install(DIRECTORY ${PROJECT_SOURCE_DIR}/engine/include/jade DESTINATION ${CMAKE_INSTALL_INCLUDEDIR}
        FILES_MATCHING PATTERN "*.hpp")
install(TARGETS jade jade_shaders EXPORT jadeTargets ARCHIVE DESTINATION ${CMAKE_INSTALL_LIBDIR})
install(TARGETS jade_io EXPORT jadeIoTargets ARCHIVE DESTINATION ${CMAKE_INSTALL_LIBDIR})
install(EXPORT jadeTargets NAMESPACE jade:: DESTINATION ${JADE_CMAKE_DIR})
install(EXPORT jadeIoTargets NAMESPACE jade:: DESTINATION ${JADE_CMAKE_DIR})

configure_package_config_file(${PROJECT_SOURCE_DIR}/cmake/jadeConfig.cmake.in
  ${PROJECT_BINARY_DIR}/jadeConfig.cmake INSTALL_DESTINATION ${JADE_CMAKE_DIR})
write_basic_package_version_file(${PROJECT_BINARY_DIR}/jadeConfigVersion.cmake
  VERSION ${PROJECT_VERSION} COMPATIBILITY SameMinorVersion)
install(FILES ${PROJECT_BINARY_DIR}/jadeConfig.cmake ${PROJECT_BINARY_DIR}/jadeConfigVersion.cmake
        DESTINATION ${JADE_CMAKE_DIR})
