#include "face_files.h"

#include "layouts.h"
#include "text.h"

#include <OpenImageIO/imageio.h>

#include <algorithm>
#include <set>

namespace mipgloss::io_detail {

namespace fs = std::filesystem;

namespace {

struct Family {
    const char* description;
    std::array<const char*, 6> tokens;  // GL order +X -X +Y -Y +Z -Z
};
// right/left/top/bottom/front/back and rt/lf/up/dn/ft/bk map right=+X, top=+Y, front=+Z.
constexpr std::array<Family, 4> kFamilies{{
    {"px/nx/py/ny/pz/nz", {"px", "nx", "py", "ny", "pz", "nz"}},
    {"posx/negx/posy/negy/posz/negz", {"posx", "negx", "posy", "negy", "posz", "negz"}},
    {"right/left/top/bottom/front/back", {"right", "left", "top", "bottom", "front", "back"}},
    {"rt/lf/up/dn/ft/bk", {"rt", "lf", "up", "dn", "ft", "bk"}},
}};


}  // namespace

// Every way a (lower-case) stem can be read as a family member, longest token first.
std::vector<FaceName> familyReadings(const std::string& stemLower) {
    std::vector<std::pair<std::size_t, FaceName>> found;
    for (int fam = 0; fam < static_cast<int>(kFamilies.size()); ++fam) {
        for (const char* token : kFamilies[static_cast<std::size_t>(fam)].tokens) {
            const std::string t = token;
            if (stemLower.size() >= t.size() &&
                stemLower.compare(stemLower.size() - t.size(), t.size(), t) == 0)
                found.push_back({t.size(), {fam, stemLower.substr(0, stemLower.size() - t.size())}});
        }
    }
    std::stable_sort(found.begin(), found.end(),
                     [](const auto& a, const auto& b) { return a.first > b.first; });
    std::vector<FaceName> out;
    for (auto& f : found) out.push_back(std::move(f.second));
    return out;
}

namespace {

const std::set<std::string>& imageExtensions() {
    static const std::set<std::string> exts = [] {
        std::set<std::string> e;
        // "openexr:exr,sxr,mxr;jpeg:jpg,jpe,jpeg,jif,jfif,jfi;..."
        const std::string list = OIIO::get_string_attribute("extension_list");
        std::size_t pos = 0;
        while (pos < list.size()) {
            const std::size_t end = std::min(list.find(';', pos), list.size());
            const std::string entry = list.substr(pos, end - pos);
            const std::size_t colon = entry.find(':');
            std::size_t p = colon == std::string::npos ? 0 : colon + 1;
            while (p < entry.size()) {
                const std::size_t comma = std::min(entry.find(',', p), entry.size());
                if (comma > p) {
                    // Appended rather than "." + ...: GCC 12's -Wrestrict misreads that at -O3.
                    std::string ext(".");
                    ext += lower(entry.substr(p, comma - p));
                    e.insert(std::move(ext));
                }
                p = comma + 1;
            }
            pos = end + 1;
        }
        for (const char* x : {".exr", ".hdr", ".png", ".jpg", ".jpeg", ".tif", ".tiff"}) e.insert(x);
        return e;
    }();
    return exts;
}

}  // namespace

std::map<std::string, std::vector<fs::path>> imagesByStem(const fs::path& dir) {
    std::map<std::string, std::vector<fs::path>> out;
    std::error_code ec;
    for (const auto& entry : fs::directory_iterator(dir, ec)) {
        if (!entry.is_regular_file(ec)) continue;
        const fs::path& p = entry.path();
        if (!imageExtensions().count(lower(p.extension().string()))) continue;
        out[lower(p.stem().string())].push_back(p);
    }
    for (auto& [stem, files] : out) std::sort(files.begin(), files.end());
    return out;
}


FaceSet lookUpFaces(const std::map<std::string, std::vector<fs::path>>& byStem, const FaceName& name,
                    const std::string& preferredExt) {
    FaceSet set;
    const Family& fam = kFamilies[static_cast<std::size_t>(name.family)];
    for (std::size_t i = 0; i < 6; ++i) {
        const auto it = byStem.find(name.prefix + fam.tokens[i]);
        if (it == byStem.end()) continue;
        fs::path pick = it->second.front();
        for (const fs::path& p : it->second)
            if (lower(p.extension().string()) == preferredExt) pick = p;
        set.files[i] = pick;
        ++set.found;
    }
    return set;
}

[[noreturn]] void throwMissingFaces(const fs::path& where, const FaceSet& set, const FaceName& name,
                                   Handedness handedness) {
    const Family& fam = kFamilies[static_cast<std::size_t>(name.family)];
    std::string reason;
    for (std::size_t i = 0; i < 6; ++i) {
        if (!set.files[i].empty()) continue;
        Face face = kAllFaces[i];
        if (handedness == Handedness::Left && (face == Face::PZ || face == Face::NZ))
            face = face == Face::PZ ? Face::NZ : Face::PZ;
        if (!reason.empty()) reason += "; ";
        reason += std::string("missing face ") + faceLabel(face) + ": no file named " +
                  name.prefix + fam.tokens[i] + ".<image extension>";
    }
    reason += " (naming family " + std::string(fam.description) + ")";
    throw EnvError(where, reason);
}

CubeMap cubeFromFaceFiles(const std::array<fs::path, 6>& files, Handedness handedness,
                          ImportReport& report, const Progress& progress) {
    std::array<Image, 6> images;
    for (std::size_t i = 0; i < 6; ++i) {
        images[i] = readImageFile(files[i], report);
        const Image& img = images[i];
        if (img.width != img.height)
            throw EnvError(files[i], "face image is " + sizeText(img.width, img.height) +
                                         ", cube faces must be square");
        if (i > 0 && img.width != images[0].width)
            throw EnvError(files[i], "face image is " + sizeText(img.width, img.height) + " but " +
                                         files[0].string() + " is " +
                                         sizeText(images[0].width, images[0].height) +
                                         "; all six faces must have the same size");
        reportProgress(progress, "import", 0.9f * static_cast<float>(i + 1) / 6.0f);
    }
    const int n = images[0].width;
    CubeMap cube(n);
    // Right-handed names go to their GL faces as they are. A left-handed skybox is the mirror
    // image: front and back swap, the side faces read mirrored left-right, top anti-transposed
    // and bottom transposed (import.h gives the measurement and Irrlicht's geometry behind it).
    using enum Face;
    static constexpr std::array<Face, 6> kRightFace{PX, NX, PY, NY, PZ, NZ};
    static constexpr std::array<Place, 6> kRightPlace{Place::AsIs, Place::AsIs, Place::AsIs,
                                                     Place::AsIs, Place::AsIs, Place::AsIs};
    static constexpr std::array<Face, 6> kLeftFace{PX, NX, PY, NY, NZ, PZ};
    static constexpr std::array<Place, 6> kLeftPlace{Place::Mirror, Place::Mirror,
                                                    Place::AntiTranspose, Place::Transpose,
                                                    Place::Mirror, Place::Mirror};
    const bool left = handedness == Handedness::Left;
    for (std::size_t i = 0; i < 6; ++i)
        copyFace(images[i], 0, 0, n, cube, left ? kLeftFace[i] : kRightFace[i],
                 left ? kLeftPlace[i] : kRightPlace[i]);
    return cube;
}


}  // namespace mipgloss::io_detail
