// What the asset readers share (internal to mipgloss_assets; asset.h is the interface): reading a
// file whole, refused with the asset's own error, and the glTF reader's file entry point for
// loadAsset.
#pragma once

#include "mipgloss/assets/asset.h"

#include <filesystem>
#include <vector>

namespace mipgloss {

// The file's bytes; AssetError (naming it) when it is not there or cannot be opened.
std::vector<unsigned char> readAssetFile(const std::filesystem::path& path);

// A .gltf or .glb file, its external buffers read beside it (formats/gltf.cpp).
Asset loadGltfFile(const std::filesystem::path& path);

}  // namespace mipgloss
