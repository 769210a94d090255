// The decoded images of material texture maps, one per image however many materials read it
// (TextureRef::key), decoded with OpenImageIO (io/texture.h) on worker threads, never on the
// caller's. As gltfio's ResourceLoader, a cache is its caller's, never the process's: one per
// document (the window's scene document, filled by its BackgroundWorker) or per command
// (`mipgloss render`, a thumbnail); that caller load()s, and the renderer it hands the cache to
// (Renderer::setTextures) only find()s what is there, drawing a material without the maps still
// missing.
//
// GPU memory budget (docs/assets.md): each image at most maxSize on a side (4096 by default,
// halved until it fits), and all of them together at most budgetBytes (1 GiB of RGBA8 by default;
// mip levels add a third on the GPU): past it, the largest images are halved again. Each
// downsizing is a warning naming the image and both sizes.
#pragma once

#include "mipgloss/assets/asset.h"
#include "mipgloss/io/texture.h"
#include "mipgloss/scene/scene.h"

#include <cstddef>
#include <map>
#include <memory>
#include <mutex>
#include <string>
#include <vector>

namespace mipgloss {

inline constexpr std::size_t kDefaultTextureBudgetBytes = std::size_t(1) << 30;

class TextureCache {
public:
    explicit TextureCache(int maxSize = kDefaultMaxTextureSize, std::size_t budgetBytes = kDefaultTextureBudgetBytes)
        : maxSize_(maxSize), budgetBytes_(budgetBytes) {}

    // Decodes each image in `refs` not decoded (or refused) yet, in parallel. A glTF's embedded
    // image comes from `kept` when it is there (Asset::images, from the parse that read the
    // asset); otherwise its file is parsed once in this call for all its images (gltfImages).
    // Returns the warnings (a missing or undecodable image: the maps reading it are drawn without
    // it; downsizing), each naming the file, once per image.
    std::vector<std::string> load(const std::vector<TextureRef>& refs, const EncodedImages& kept = {});

    // The image for `ref`, or null (not loaded, or refused).
    std::shared_ptr<const TextureImage> find(const TextureRef& ref) const;
    // Why `ref` was refused, "" when it was not.
    std::string problem(const TextureRef& ref) const;

    std::size_t bytes() const;   // all decoded images, RGBA8
    std::size_t images() const;

private:
    int maxSize_;
    std::size_t budgetBytes_;
    mutable std::mutex mutex_;
    std::map<std::string, std::shared_ptr<const TextureImage>> images_;
    std::map<std::string, std::string> problems_;
};

// Every texture the scene's materials read (used or not by an object), each image once.
std::vector<TextureRef> texturesOf(const Scene& scene);

}  // namespace mipgloss
