// The glTF fuzz target's structure-aware mutations (issue 34): libFuzzer's byte mutations rarely
// turn a valid glTF into one that is wrong the way hostile assets are (an index past 2^32 that
// wraps, nesting 30 000 deep, a field of the wrong kind, a path out of the asset's folder), so
// half of fuzz_gltf_import's mutations are these, made on the JSON's tokens (valid JSON or not)
// and, in a .glb, on its JSON chunk with the container's lengths kept right.
#pragma once

#include <cstdint>
#include <random>
#include <string>
#include <vector>

namespace mipgloss::fuzz {

enum class GltfMutation {
    InterestingNumber,  // a number made 2^32 + n, −1, 2^31, 1e308, −0, 0.5, ...
    IndexWrap,          // a number after an index key ("mesh", "bufferView", ...) made n + 2^32 or −n
    DeepNesting,        // a value replaced by arrays or objects nested 63 to 30 000 deep
    WrongKind,          // a value replaced by one of another kind (string, null, true, {}, [], [1, 2])
    HostileString,      // a string made a path out of the folder, a %00, an absolute path, a bad data URI
    DuplicateValue,     // a value repeated after itself (arrays grow, a key appears twice)
};
inline constexpr int kGltfMutationCount = 6;

// `json` mutated once by `kind`, at a place drawn from `rng`; unchanged when it has no such place
// (no number, no string). Never longer than maxSize (a nesting that would be is made shallower).
std::string mutateGltfJson(const std::string& json, GltfMutation kind, std::minstd_rand& rng, std::size_t maxSize);

// The whole input (a .gltf's text, or a .glb whose JSON chunk is mutated and its chunk and file
// lengths rewritten), one mutation of a kind drawn from `rng`; empty when it cannot be mutated so
// (not JSON-like, or the result would pass maxSize).
std::vector<std::uint8_t> mutateGltf(const std::vector<std::uint8_t>& input, std::minstd_rand& rng, std::size_t maxSize);

}  // namespace mipgloss::fuzz
