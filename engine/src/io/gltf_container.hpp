// io/gltf_container.hpp - the byte-level parts of writing glTF (private to jade_io): base64 for
// data URIs and the GLB container, shared by save_baked_gltf and save_baked_asset.
#pragma once

#include <string>
#include <vector>

namespace jade::io {

/// RFC 4648 base64 with padding, as glTF data URIs hold it.
std::string base64(const std::vector<unsigned char>& data);

/// A GLB file: 12-byte header, the JSON chunk padded with spaces, the BIN chunk (omitted when
/// `bin` is empty) padded with zeros, every chunk 4-byte aligned. Fails naming `name` past 4 GiB.
std::string glb_container(const std::string& name, std::string json_text, const std::vector<unsigned char>& bin);

}  // namespace jade::io
