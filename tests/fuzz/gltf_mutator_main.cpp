// fuzz_gltf_import's custom mutator (libFuzzer calls it instead of its own byte mutations): half
// the time the structure-aware mutations of gltf_mutator.h, else libFuzzer's own, so the corpus
// still grows by coverage from both.
#include "gltf_mutator.h"

#include <algorithm>
#include <cstring>

extern "C" std::size_t LLVMFuzzerMutate(std::uint8_t* data, std::size_t size, std::size_t maxSize);

extern "C" std::size_t LLVMFuzzerCustomMutator(std::uint8_t* data, std::size_t size, std::size_t maxSize,
                                               unsigned int seed) {
    std::minstd_rand rng(seed);
    if (rng() % 2 == 0) {
        const std::vector<std::uint8_t> input(data, data + size);
        const std::vector<std::uint8_t> out = mipgloss::fuzz::mutateGltf(input, rng, maxSize);
        if (!out.empty() && out.size() <= maxSize) {
            std::memcpy(data, out.data(), out.size());
            return out.size();
        }
    }
    return LLVMFuzzerMutate(data, size, maxSize);
}
