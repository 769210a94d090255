#include "mipgloss/assets/textures.h"

#include "mipgloss/assets/asset.h"

#include <tbb/parallel_for.h>

#include <algorithm>
#include <filesystem>
#include <map>
#include <mutex>
#include <set>

namespace mipgloss {

namespace {

// The encoded bytes of each embedded glTF image in `todo` (null for a plain image file, or where
// `problems` says why there are none): the caller's kept ones, else each file's images from one
// parse of it, the files parsed in parallel.
std::vector<std::shared_ptr<const EncodedImage>> encodedImagesOf(const std::vector<TextureRef>& todo,
                                                                 const EncodedImages& kept,
                                                                 std::vector<std::string>& problems) {
    std::vector<std::shared_ptr<const EncodedImage>> encoded(todo.size());
    std::map<std::string, std::vector<std::size_t>> byFile;
    for (std::size_t i = 0; i < todo.size(); ++i) {
        if (todo[i].image < 0) continue;
        if (const auto it = kept.find(todo[i].key()); it != kept.end() && it->second)
            encoded[i] = it->second;
        else
            byFile[todo[i].file].push_back(i);
    }
    const std::vector<std::pair<const std::string, std::vector<std::size_t>>*> files = [&] {
        std::vector<std::pair<const std::string, std::vector<std::size_t>>*> out;
        for (auto& entry : byFile) out.push_back(&entry);
        return out;
    }();
    tbb::parallel_for(std::size_t(0), files.size(), [&](std::size_t f) {
        const std::filesystem::path file = files[f]->first;
        const std::vector<std::size_t>& refs = files[f]->second;
        try {
            std::vector<EncodedImage> images = gltfImages(file);
            for (const std::size_t i : refs) {
                const int image = todo[i].image;
                if (static_cast<std::size_t>(image) >= images.size())
                    problems[i] = AssetError(file, "image " + std::to_string(image) + " is not in the file (it has " +
                                                       std::to_string(images.size()) + ")").what();
                else if (images[static_cast<std::size_t>(image)].bytes.empty())
                    problems[i] = AssetError(file, "image " + std::to_string(image) + " has no data").what();
                else  // refs are one per key, so each image is taken once: moved, not copied
                    encoded[i] = std::make_shared<const EncodedImage>(std::move(images[static_cast<std::size_t>(image)]));
            }
        } catch (const FileError& e) {
            for (const std::size_t i : refs) problems[i] = e.what();
        } catch (const std::exception& e) {  // out of memory on a huge file, ...
            for (const std::size_t i : refs) problems[i] = todo[i].key() + ": " + e.what();
        }
    });
    return encoded;
}

}  // namespace

std::vector<std::string> TextureCache::load(const std::vector<TextureRef>& refs, const EncodedImages& kept) {
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
    std::vector<std::string> unread(todo.size());
    const std::vector<std::shared_ptr<const EncodedImage>> encoded = encodedImagesOf(todo, kept, unread);
    // The budget, planned from the headers before a pixel is decoded: each image's side limit is
    // maxSize, halved for the largest images until the planned total fits, so a file whose headers
    // promise more than the budget is decoded downsized (as its rows are read: texture.h), never
    // at full size first. An image whose header cannot be read is left to its decoding to refuse.
    std::vector<TextureSize> header(todo.size()), planned(todo.size());
    tbb::parallel_for(std::size_t(0), todo.size(), [&](std::size_t i) {
        if (!unread[i].empty()) return;
        try {
            header[i] = encoded[i] ? textureSizeFromMemory(encoded[i]->bytes, todo[i].key(), encoded[i]->mimeType)
                                   : textureSize(todo[i].file);
            planned[i] = fittedTextureSize(header[i], maxSize_);
        } catch (const std::exception&) {
        }
    });
    // Some decoders hold the whole image whatever is asked of them (WebP, interlaced PNG, a
    // progressive JPEG's coefficients): up to 1 GiB for a texture of kMaxTexturePixels. One such
    // large image is decoded at a time, so the peak is one of them, not one per core (three
    // 10 KB WebP files of 16383², `render --mesh` on 2 cores: 2.18 GB peak, 6.2 s → 1.33 GB, 8.5 s).
    std::mutex oneLargeDecode;
    constexpr std::size_t kLargeDecodeBytes = std::size_t(64) << 20;
    std::vector<int> sideLimit(todo.size(), maxSize_);
    {
        std::size_t total = bytes();
        for (const TextureSize& p : planned) total += p.rgbaBytes();
        while (total > budgetBytes_) {
            std::size_t largest = todo.size();
            for (std::size_t i = 0; i < todo.size(); ++i)
                if (planned[i].rgbaBytes() > 0 && (largest == todo.size() || planned[i].rgbaBytes() > planned[largest].rgbaBytes()))
                    largest = i;
            if (largest == todo.size() || (planned[largest].width <= 1 && planned[largest].height <= 1)) break;
            sideLimit[largest] = std::max(planned[largest].width, planned[largest].height) / 2;
            total -= planned[largest].rgbaBytes();
            planned[largest] = fittedTextureSize(planned[largest], sideLimit[largest]);
            total += planned[largest].rgbaBytes();
        }
    }
    tbb::parallel_for(std::size_t(0), todo.size(), [&](std::size_t i) {
        if (!unread[i].empty()) {
            results[i].problem = unread[i];
            return;
        }
        try {
            const int side = sideLimit[i];
            std::unique_lock<std::mutex> large(oneLargeDecode, std::defer_lock);
            if (header[i].rgbaBytes() > kLargeDecodeBytes) large.lock();
            results[i].image = std::make_shared<TextureImage>(
                encoded[i] ? decodeTextureFromMemory(encoded[i]->bytes, todo[i].key(), encoded[i]->mimeType, side)
                           : decodeTexture(todo[i].file, side));
            if (large.owns_lock()) large.unlock();
            TextureImage& image = *results[i].image;
            // Downsized for the budget, not for maxSize: its one downsizing warning says so.
            if (side < maxSize_ && (image.width != image.fileWidth || image.height != image.fileHeight))
                image.warnings.back() = "texture of " + std::to_string(image.fileWidth) + " x " + std::to_string(image.fileHeight) +
                                        " downsized to " + std::to_string(image.width) + " x " + std::to_string(image.height) +
                                        " to keep all textures within the " + std::to_string(budgetBytes_ >> 20) + " MiB budget";
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
    // Over the budget still (another load() stored images between this one's plan and now: the
    // plan read bytes() unlocked): halve the largest new image until the total fits.
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
