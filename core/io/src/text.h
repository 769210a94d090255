// Small text helpers shared by the file readers (not part of the io interface).
#pragma once

#include "mipgloss/ibl/cubemap.h"

#include <cctype>
#include <string>

namespace mipgloss::io_detail {

inline std::string lower(std::string s) {
    for (char& c : s) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
    return s;
}

inline std::string sizeText(int w, int h) { return std::to_string(w) + "x" + std::to_string(h); }

// "+X", "-X", ... for messages.
inline const char* faceLabel(Face f) {
    static constexpr const char* kLabels[6] = {"+X", "-X", "+Y", "-Y", "+Z", "-Z"};
    return kLabels[static_cast<int>(f)];
}

}  // namespace mipgloss::io_detail
