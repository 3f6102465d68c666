// A glTF scene written for a test: one node per mesh, with its material index and node extras,
// the buffers embedded as a base64 data URI (test::out("scene/NAME.gltf")).
#pragma once

#include <jade/mesh.hpp>

#include <filesystem>
#include <string>
#include <vector>

namespace jade::test {

struct TestObject {
    TriangleMesh mesh;
    int material = -1;
    std::string node_extras;  // JSON, or empty
};

/// A .gltf with one node per object and the given "materials" array (JSON text).
std::filesystem::path write_gltf(const std::string& name, const std::vector<TestObject>& objects,
                                 const std::string& materials);

}  // namespace jade::test
