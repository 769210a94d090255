#include "entries.h"

namespace mipgloss::fuzz {

Entry entryNamed(std::string_view target) {
    if (target == "environment_import") return &environmentImport;
    if (target == "mesh_import") return &meshImport;
#ifdef MIPGLOSS_FUZZ_HAVE_UI
    if (target == "scene_file") return &sceneFile;
    if (target == "library_file") return &libraryFile;
#endif
    return nullptr;
}

}  // namespace mipgloss::fuzz
