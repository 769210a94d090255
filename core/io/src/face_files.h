// Six face files: the naming families that identify them, finding a set beside a file or in a
// folder, and turning the six images into a cube (with the left-handed mapping import.h measures).
// Internal to the io library.
#pragma once

#include "decode.h"

#include <array>
#include <filesystem>
#include <map>
#include <string>
#include <vector>

namespace mipgloss::io_detail {

// A guess that a stem is `prefix + token` of a family.
struct FaceName {
    int family;
    std::string prefix;  // lower case
};

// The files of one family and prefix that exist.
struct FaceSet {
    std::array<std::filesystem::path, 6> files;  // GL order as named (before any handedness change)
    int found = 0;
};

// Every way a (lower-case) stem can be read as a family member, longest token first.
std::vector<FaceName> familyReadings(const std::string& stemLower);

// Image files of a folder by lower-case stem.
std::map<std::string, std::vector<std::filesystem::path>> imagesByStem(const std::filesystem::path& dir);

// The members of `name`'s family present in `byStem`, preferring `preferredExt` among files that
// share a stem.
FaceSet lookUpFaces(const std::map<std::string, std::vector<std::filesystem::path>>& byStem,
                    const FaceName& name, const std::string& preferredExt);

// Throws EnvError at `where` listing every face the set lacks, by the name it would have.
[[noreturn]] void throwMissingFaces(const std::filesystem::path& where, const FaceSet& set,
                                   const FaceName& name, Handedness handedness);

// Reads six square face images of one size into a cube (right-handed: as they are; left-handed:
// mirrored as import.h describes). Throws EnvError naming the offending file.
CubeMap cubeFromFaceFiles(const std::array<std::filesystem::path, 6>& files, Handedness handedness,
                          ImportReport& report, const Progress& progress);

}  // namespace mipgloss::io_detail
