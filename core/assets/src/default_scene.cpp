#include "mipgloss/assets/default_scene.h"

#include "mipgloss/assets/mesh_files.h"

#include <cstddef>
#include <memory>

// Generated at build time from resources/meshes/teapot.obj (core/cmake/embed_file.cmake).
namespace mipgloss::embedded {
extern const unsigned char default_teapot_obj[];
extern const std::size_t default_teapot_obj_size;
}  // namespace mipgloss::embedded

namespace mipgloss {

Mesh defaultTeapot() {
    return loadMeshFromMemory({embedded::default_teapot_obj, embedded::default_teapot_obj_size}, "teapot.obj");
}

Scene makeFigure1Scene() { return makeFigure1Scene(std::make_shared<const Mesh>(defaultTeapot())); }

}  // namespace mipgloss
