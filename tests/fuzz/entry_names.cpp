#include "entries.h"

namespace mipgloss::fuzz {

Entry entryNamed(std::string_view target) {
    if (target == "environment_import") return &environmentImport;
    if (target == "mesh_import") return &meshImport;
    if (target == "gltf_import") return &gltfImport;
    if (target == "mtl_import") return &mtlImport;
#ifdef MIPGLOSS_FUZZ_HAVE_UI
    if (target == "scene_file") return &sceneFile;
    if (target == "library_file") return &libraryFile;
#endif
    return nullptr;
}

}  // namespace mipgloss::fuzz
