// The outline pass: the highlighted object's silhouette band (Renderer::setHighlightedObject).
#include "renderer_impl.h"

#include <glm/gtc/type_ptr.hpp>

#include <cmath>

namespace mipgloss::ui {

// The highlighted object's outline (setHighlightedObject), after everything else so nothing
// covers it: its silhouette marked in the stencil, then the object pushed outward along its
// normals drawn where the stencil is not marked. Depth is neither tested nor written, so the
// whole silhouette shows, also where another object hides it.
void Renderer::Impl::drawOutline(const Scene& scene, const glm::mat4& viewProjection, int width, int height) {
    if (highlighted < 0 || highlighted >= static_cast<int>(scene.objects.size())) return;
    const SceneObject& object = scene.objects[static_cast<std::size_t>(highlighted)];
    if (!object.visible || !object.mesh || object.mesh->indices.empty()) return;
    const GpuMesh& mesh = gpuMesh(object.mesh);
    QOpenGLShaderProgram& program = *outlineProgram;
    program.bind();
    const glm::mat4 model = object.transform.matrix();
    const glm::mat3 rotation = glm::mat3(model) / std::max(std::abs(object.transform.scale), 1e-30f);
    gl->glUniformMatrix4fv(program.uniformLocation("uViewProjection"), 1, GL_FALSE, glm::value_ptr(viewProjection));
    gl->glUniformMatrix4fv(program.uniformLocation("uModel"), 1, GL_FALSE, glm::value_ptr(model));
    gl->glUniformMatrix3fv(program.uniformLocation("uNormalMatrix"), 1, GL_FALSE, glm::value_ptr(rotation));
    gl->glUniform2f(program.uniformLocation("uViewportSize"), static_cast<float>(width), static_cast<float>(height));
    // An orange that reads on sky and ground alike, bright enough to survive the tone map.
    gl->glUniform3f(program.uniformLocation("uColour"), 4.0f, 1.1f, 0.05f);
    gl->glDisable(GL_DEPTH_TEST);
    gl->glDepthMask(GL_FALSE);
    gl->glEnable(GL_STENCIL_TEST);
    gl->glBindVertexArray(mesh.vao);
    // 1: the silhouette, stencil only.
    gl->glStencilFunc(GL_ALWAYS, 1, 0xFF);
    gl->glStencilOp(GL_KEEP, GL_KEEP, GL_REPLACE);
    gl->glColorMask(GL_FALSE, GL_FALSE, GL_FALSE, GL_FALSE);
    gl->glUniform1f(program.uniformLocation("uWidthPixels"), 0.0f);
    gl->glDrawElements(GL_TRIANGLES, mesh.indexCount, GL_UNSIGNED_INT, nullptr);
    // 2: the band around it.
    gl->glColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
    gl->glStencilFunc(GL_NOTEQUAL, 1, 0xFF);
    gl->glStencilMask(0x00);
    gl->glUniform1f(program.uniformLocation("uWidthPixels"), kOutlineWidthPixels);
    gl->glDrawElements(GL_TRIANGLES, mesh.indexCount, GL_UNSIGNED_INT, nullptr);
    counters.drawCalls += 2;
    gl->glStencilMask(0xFF);
    gl->glDisable(GL_STENCIL_TEST);
    gl->glDepthMask(GL_TRUE);
    gl->glEnable(GL_DEPTH_TEST);
    gl->glBindVertexArray(0);
    program.release();
}

}  // namespace mipgloss::ui
