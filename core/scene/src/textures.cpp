#include "mipgloss/scene/textures.h"

#include "mipgloss/scene/asset.h"

#include <tbb/parallel_for.h>

#include <algorithm>
#include <set>

namespace mipgloss {

TextureImage decodeTextureRef(const TextureRef& ref, int maxSize) {
    if (ref.image < 0) return decodeTexture(ref.file, maxSize);
    const EncodedImage encoded = gltfImageBytes(ref.file, ref.image);
    return decodeTextureFromMemory(encoded.bytes, ref.key(), encoded.mimeType, maxSize);
}

std::vector<std::string> TextureCache::load(const std::vector<TextureRef>& refs) {
    std::vector<TextureRef> todo;
    {
        std::lock_guard lock(mutex_);
        std::set<std::string> seen;
        // key() names the image, whatever channel a map reads of it.
        for (const TextureRef& ref : refs) {
            if (ref.empty()) continue;
            const std::string key = ref.key();
            if (images_.count(key) || problems_.count(key) || !seen.insert(key).second) continue;
            todo.push_back(ref);
        }
    }
    struct Result {
        std::shared_ptr<TextureImage> image;
        std::string problem;
    };
    std::vector<Result> results(todo.size());
    tbb::parallel_for(std::size_t(0), todo.size(), [&](std::size_t i) {
        try {
            results[i].image = std::make_shared<TextureImage>(decodeTextureRef(todo[i], maxSize_));
        } catch (const FileError& e) {
            results[i].problem = e.what();
        } catch (const std::exception& e) {  // out of memory on a huge image, ...
            results[i].problem = todo[i].key() + ": " + e.what();
        }
    });
    std::vector<std::string> warnings;
    std::lock_guard lock(mutex_);
    std::size_t total = 0;
    for (const auto& [key, image] : images_) total += image->bytes();
    for (const Result& r : results)
        if (r.image) total += r.image->bytes();
    // Over the budget: halve the largest new image until the total fits.
    while (total > budgetBytes_) {
        Result* largest = nullptr;
        for (Result& r : results)
            if (r.image && (!largest || r.image->bytes() > largest->image->bytes())) largest = &r;
        if (!largest || (largest->image->width <= 1 && largest->image->height <= 1)) break;
        const std::size_t before = largest->image->bytes();
        downsizeTexture(*largest->image, std::max(largest->image->width, largest->image->height) / 2);
        total -= before - largest->image->bytes();
        largest->image->warnings.push_back("texture downsized to " + std::to_string(largest->image->width) + " x " +
                                           std::to_string(largest->image->height) +
                                           " to keep all textures within the " +
                                           std::to_string(budgetBytes_ >> 20) + " MiB budget");
    }
    for (std::size_t i = 0; i < todo.size(); ++i) {
        const std::string key = todo[i].key();
        if (results[i].image) {
            for (const std::string& w : results[i].image->warnings)
                warnings.push_back(w.rfind(key, 0) == 0 ? w : key + ": " + w);
            images_[key] = results[i].image;
        } else {
            problems_[key] = results[i].problem;
            warnings.push_back(results[i].problem + " (the maps that read it are drawn without it)");
        }
    }
    return warnings;
}

std::shared_ptr<const TextureImage> TextureCache::find(const TextureRef& ref) const {
    std::lock_guard lock(mutex_);
    const auto it = images_.find(ref.key());
    return it == images_.end() ? nullptr : it->second;
}

std::string TextureCache::problem(const TextureRef& ref) const {
    std::lock_guard lock(mutex_);
    const auto it = problems_.find(ref.key());
    return it == problems_.end() ? std::string() : it->second;
}

std::size_t TextureCache::bytes() const {
    std::lock_guard lock(mutex_);
    std::size_t total = 0;
    for (const auto& [key, image] : images_) total += image->bytes();
    return total;
}

std::size_t TextureCache::images() const {
    std::lock_guard lock(mutex_);
    return images_.size();
}

TextureCache& sharedTextureCache() {
    static TextureCache cache;
    return cache;
}

std::vector<TextureRef> texturesOf(const Scene& scene) {
    std::vector<TextureRef> out;
    std::set<std::string> seen;
    for (const NamedMaterial& m : scene.materials) {
        if (!m.material.layered) continue;
        for (const TextureRef& t : m.material.layers.maps.textures())
            if (seen.insert(t.key()).second) out.push_back(t);
    }
    return out;
}

}  // namespace mipgloss
