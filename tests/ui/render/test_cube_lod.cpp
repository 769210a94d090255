// The exact mask's level of detail (resources/shaders/cube_lod.glsl) against the level texture()
// really reads: a cube whose level k holds the value k everywhere, read trilinearly, returns the
// level it read (the blend of levels ⌊λ⌋ and ⌈λ⌉ by λ's fraction is λ itself). On a sphere seen
// large and small, reflecting (every face, its edges and corners, footprints from magnified to
// the last level), cubeLevelOfDetail must agree with the read, and say "base level only"
// (λ ≤ 0) exactly where the read touched no other level. textureQueryLod is printed beside it,
// to show why the mask no longer trusts it.
#include "mipgloss/scene/camera.h"
#include "mipgloss/scene/mesh.h"
#include "mipgloss/ui/gl_format.h"

#include <gtest/gtest.h>

#include <QFile>
#include <QOffscreenSurface>
#include <QOpenGLContext>
#include <QOpenGLFunctions_4_1_Core>
#include <QOpenGLShaderProgram>
#include <QOpenGLVersionFunctionsFactory>

#include <glm/gtc/type_ptr.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <vector>

namespace mipgloss {
namespace {

const char* kVertex = R"(#version 410 core
layout(location = 0) in vec3 aPosition;
uniform mat4 uViewProjection;
out vec3 vPosition;
void main() { vPosition = aPosition; gl_Position = uViewProjection * vec4(aPosition, 1.0); }
)";

// r: the reflection off a unit sphere at the origin, as object.frag makes it.
const char* kFragment = R"(#version 410 core
in vec3 vPosition;
uniform vec3 uEye;
uniform samplerCube uCube;
uniform float uSize;
layout(location = 0) out vec4 outColour;
CUBE_LOD
void main() {
    vec3 n = normalize(vPosition);
    vec3 r = reflect(-normalize(uEye - vPosition), n);
    outColour = vec4(texture(uCube, r).r, cubeLevelOfDetail(r, uSize), textureQueryLod(uCube, r).y, 1.0);
}
)";

struct Agreement {
    int pixels = 0;
    int betweenLevels = 0;      // pixels whose read is strictly between the base and the last level
    double worstBetween = 0.0;  // largest |derived − read| there
    double meanBetween = 0.0;
    int maskWrong = 0;          // base-only by one and not the other, outside ±0.05 of the edge
    int queryMaskWrong = 0;     // the same with textureQueryLod
    double worstQuery = 0.0;    // largest |textureQueryLod − read| between levels
    int exactButNot = 0;        // marked exact by the AOV's rule, but read above the base
    int baseOnlyUnmarked = 0;   // read the base alone, left unmarked by the rule's margin
};

TEST(CubeLevelOfDetail, AgreesWithTheLevelTextureReads) {
    QOffscreenSurface surface;
    QOpenGLContext context;
    surface.setFormat(ui::surfaceFormat());
    surface.create();
    context.setFormat(ui::surfaceFormat());
    ASSERT_TRUE(surface.isValid() && context.create() && context.makeCurrent(&surface)) << "no OpenGL 4.1";
    auto* gl = QOpenGLVersionFunctionsFactory::get<QOpenGLFunctions_4_1_Core>(&context);
    ASSERT_TRUE(gl && gl->initializeOpenGLFunctions());

    QFile lodFile(QStringLiteral(":/mipgloss/shaders/cube_lod.glsl"));
    ASSERT_TRUE(lodFile.open(QIODevice::ReadOnly));
    QByteArray fragment(kFragment);
    fragment.replace("CUBE_LOD", lodFile.readAll());
    QOpenGLShaderProgram program;
    ASSERT_TRUE(program.addShaderFromSourceCode(QOpenGLShader::Vertex, kVertex)) << program.log().toStdString();
    ASSERT_TRUE(program.addShaderFromSourceCode(QOpenGLShader::Fragment, fragment)) << program.log().toStdString();
    ASSERT_TRUE(program.link()) << program.log().toStdString();
    int baseOnlyPixels = 0, unmarked = 0;

    // The sphere.
    const Mesh sphere = makeSphere(96, 192);
    GLuint vao = 0, vbo = 0, ibo = 0;
    gl->glGenVertexArrays(1, &vao);
    gl->glBindVertexArray(vao);
    gl->glGenBuffers(1, &vbo);
    gl->glBindBuffer(GL_ARRAY_BUFFER, vbo);
    gl->glBufferData(GL_ARRAY_BUFFER, static_cast<GLsizeiptr>(sphere.positions.size() * sizeof(glm::vec3)),
                     sphere.positions.data(), GL_STATIC_DRAW);
    gl->glEnableVertexAttribArray(0);
    gl->glVertexAttribPointer(0, 3, GL_FLOAT, GL_FALSE, sizeof(glm::vec3), nullptr);
    gl->glGenBuffers(1, &ibo);
    gl->glBindBuffer(GL_ELEMENT_ARRAY_BUFFER, ibo);
    gl->glBufferData(GL_ELEMENT_ARRAY_BUFFER, static_cast<GLsizeiptr>(sphere.indices.size() * sizeof(std::uint32_t)),
                     sphere.indices.data(), GL_STATIC_DRAW);

    // A float target.
    constexpr int kImage = 256;
    GLuint target = 0, depth = 0, fbo = 0;
    gl->glGenTextures(1, &target);
    gl->glBindTexture(GL_TEXTURE_2D, target);
    gl->glTexImage2D(GL_TEXTURE_2D, 0, GL_RGBA32F, kImage, kImage, 0, GL_RGBA, GL_FLOAT, nullptr);
    gl->glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
    gl->glGenRenderbuffers(1, &depth);
    gl->glBindRenderbuffer(GL_RENDERBUFFER, depth);
    gl->glRenderbufferStorage(GL_RENDERBUFFER, GL_DEPTH_COMPONENT24, kImage, kImage);
    gl->glGenFramebuffers(1, &fbo);
    gl->glBindFramebuffer(GL_FRAMEBUFFER, fbo);
    gl->glFramebufferTexture2D(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_TEXTURE_2D, target, 0);
    gl->glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_DEPTH_ATTACHMENT, GL_RENDERBUFFER, depth);
    ASSERT_EQ(gl->glCheckFramebufferStatus(GL_FRAMEBUFFER), static_cast<GLenum>(GL_FRAMEBUFFER_COMPLETE));

  // A 128² cube (every pixel reads above the base: a sphere's reflections spread fast) and a 16²
  // one (its base magnified over most of the sphere seen large: the mask's own case).
  for (const int kSize : {128, 16}) {
    const int kLevels = static_cast<int>(std::log2(kSize)) + 1;
    GLuint cube = 0;
    gl->glGenTextures(1, &cube);
    gl->glBindTexture(GL_TEXTURE_CUBE_MAP, cube);
    for (int level = 0; level < kLevels; ++level) {
        const int n = kSize >> level;
        const std::vector<float> texels(static_cast<std::size_t>(n * n), static_cast<float>(level));
        for (int face = 0; face < 6; ++face)
            gl->glTexImage2D(static_cast<GLenum>(GL_TEXTURE_CUBE_MAP_POSITIVE_X + face), level, GL_R32F, n, n, 0,
                             GL_RED, GL_FLOAT, texels.data());
    }
    gl->glTexParameteri(GL_TEXTURE_CUBE_MAP, GL_TEXTURE_MAX_LEVEL, kLevels - 1);
    gl->glTexParameteri(GL_TEXTURE_CUBE_MAP, GL_TEXTURE_MIN_FILTER, GL_LINEAR_MIPMAP_LINEAR);
    gl->glTexParameteri(GL_TEXTURE_CUBE_MAP, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
    gl->glEnable(GL_TEXTURE_CUBE_MAP_SEAMLESS);

    // From filling the image (a base-level read over most of it) to 1/12 of it (deep levels).
    for (const float margin : {1.05f, 1.6f, 4.0f, 12.0f}) {
        for (const float yaw : {0.0f, 37.0f}) {
            OrbitCamera camera;
            camera.yawDegrees = yaw;
            camera.pitchDegrees = 25.0f;
            const Bounds unit{glm::vec3(-1.0f), glm::vec3(1.0f)};
            camera.frame(unit, 1.0f, margin);
            const glm::mat4 viewProjection = camera.projection(1.0f, unit) * camera.view();
            gl->glViewport(0, 0, kImage, kImage);
            gl->glClearColor(0.0f, 0.0f, 0.0f, 0.0f);
            gl->glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
            gl->glEnable(GL_DEPTH_TEST);
            program.bind();
            gl->glUniformMatrix4fv(program.uniformLocation("uViewProjection"), 1, GL_FALSE, glm::value_ptr(viewProjection));
            const glm::vec3 eye = camera.position();
            gl->glUniform3f(program.uniformLocation("uEye"), eye.x, eye.y, eye.z);
            gl->glUniform1i(program.uniformLocation("uCube"), 0);
            gl->glUniform1f(program.uniformLocation("uSize"), static_cast<float>(kSize));
            gl->glActiveTexture(GL_TEXTURE0);
            gl->glBindTexture(GL_TEXTURE_CUBE_MAP, cube);
            gl->glBindVertexArray(vao);
            gl->glDrawElements(GL_TRIANGLES, static_cast<GLsizei>(sphere.indices.size()), GL_UNSIGNED_INT, nullptr);
            std::vector<float> pixels(static_cast<std::size_t>(kImage * kImage * 4));
            gl->glReadPixels(0, 0, kImage, kImage, GL_RGBA, GL_FLOAT, pixels.data());

            Agreement a;
            for (std::size_t i = 0; i < pixels.size(); i += 4) {
                if (pixels[i + 3] < 0.5f) continue;  // off the sphere
                ++a.pixels;
                const double read = pixels[i], derived = pixels[i + 1], query = pixels[i + 2];
                const bool readBaseOnly = read < 1e-4;
                if (std::abs(derived) > 0.05 && (derived <= 0.0) != readBaseOnly) ++a.maskWrong;
                // The AOV's rule (readsBaseLevelOnly): never marks a pixel that read another level.
                if (derived <= -0.05 && !readBaseOnly) ++a.exactButNot;
                if (readBaseOnly && derived > -0.05) ++a.baseOnlyUnmarked;
                if (std::abs(query) > 0.05 && (query <= 0.0) != readBaseOnly) ++a.queryMaskWrong;
                if (read > 0.02 && read < kLevels - 1 - 0.02) {
                    ++a.betweenLevels;
                    const double e = std::abs(derived - read);
                    a.worstBetween = std::max(a.worstBetween, e);
                    a.meanBetween += e;
                    a.worstQuery = std::max(a.worstQuery, std::abs(query - read));
                }
            }
            if (a.betweenLevels) a.meanBetween /= a.betweenLevels;
            std::printf("[ CubeLevelOfDetail ] %3d² margin %5.2f yaw %4.0f: %6d pixels, %6d between levels: derived "
                        "off by %.3f mean, %.3f worst; base-only mask wrong on %d (textureQueryLod: %d wrong, "
                        "%.2f worst)\n",
                        kSize, margin, yaw, a.pixels, a.betweenLevels, a.meanBetween, a.worstBetween, a.maskWrong,
                        a.queryMaskWrong, a.worstQuery);
            EXPECT_GT(a.pixels, 100);
            EXPECT_LT(a.worstBetween, 0.1) << kSize << "² margin " << margin;
            EXPECT_EQ(a.maskWrong, 0) << kSize << "² margin " << margin;
            EXPECT_EQ(a.exactButNot, 0) << kSize << "² margin " << margin;
            unmarked += a.baseOnlyUnmarked;
            baseOnlyPixels += a.pixels - a.betweenLevels;
        }
    }
    gl->glDeleteTextures(1, &cube);
  }
  EXPECT_GT(baseOnlyPixels, 1000) << "no case read the base level alone: the mask went untested";
  std::printf("[ CubeLevelOfDetail ] base-only reads: %d, left unmarked by the 0.05 margin: %d\n", baseOnlyPixels,
              unmarked);
  EXPECT_LT(unmarked, baseOnlyPixels / 20) << "the margin costs more than 5 % of the exact pixels";
    gl->glBindFramebuffer(GL_FRAMEBUFFER, context.defaultFramebufferObject());
    gl->glDeleteFramebuffers(1, &fbo);
    gl->glDeleteRenderbuffers(1, &depth);
    gl->glDeleteTextures(1, &target);
    gl->glDeleteBuffers(1, &vbo);
    gl->glDeleteBuffers(1, &ibo);
    gl->glDeleteVertexArrays(1, &vao);
    program.removeAllShaders();
    context.doneCurrent();
}

}  // namespace
}  // namespace mipgloss
