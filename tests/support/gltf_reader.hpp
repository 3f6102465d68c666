// gltf_reader.hpp - a glTF reader for the tests, independent of Jade's own (nlohmann::json and
// its own binary decoding: GLB chunks, base64 data URIs, external files, strides, sparse
// accessors), to check what `jade bake` writes; and the Khronos glTF Validator.
#pragma once

#include <nlohmann/json.hpp>

#include <filesystem>
#include <optional>
#include <string>
#include <vector>

namespace jade::test {

struct GltfFile {
    std::filesystem::path path;
    nlohmann::json doc;
    std::vector<std::vector<unsigned char>> buffers;

    /// Accessor `index`'s elements, each as its bytes (component size × components), with
    /// sparse values applied; zeros without a bufferView.
    std::vector<std::vector<unsigned char>> elements(int index) const;
    /// A FLOAT accessor's values, flattened.
    std::vector<float> floats(int index) const;
    /// Image `index`'s encoded bytes (PNG, JPEG, ...): from its bufferView or its URI.
    std::vector<unsigned char> image(int index) const;
};

/// Parses a .gltf or .glb; throws std::runtime_error naming the file and what is wrong.
GltfFile read_gltf_file(const std::filesystem::path& path);

struct ValidatorReport {
    std::string file;
    int errors = -1, warnings = -1, infos = -1, hints = -1;
    std::vector<std::string> issues;  ///< the errors and warnings, "CODE /pointer: message"
};

/// Runs the Khronos glTF Validator (gltf-validator from the npm registry, installed by
/// third_party/install_gltf_validator.sh into the build folder if missing) on every file.
/// nullopt, with `skip` saying why, only when the machine has no Node.js; any other failure to
/// run it is a test failure (reported in `skip` too, with an empty report list).
std::optional<std::vector<ValidatorReport>> run_gltf_validator(const std::vector<std::filesystem::path>& files,
                                                               std::string* skip);

}  // namespace jade::test
