// The renderer's programs from its shader files (":/mipgloss/shaders/..."): each file's own
// `#include "x.glsl"` lines resolved, the names C++ and GLSL share defined after #version.
#pragma once

#include <QByteArray>
#include <QOpenGLShaderProgram>

#include <memory>
#include <string>

namespace mipgloss::ui {

// The shader `file` (a name under :/mipgloss/shaders/) as the compiler gets it: its #version line,
// the shared names (shaderDefines, textureUnitDefines) and `extraDefines`, then its text with
// every `#include "x.glsl"` line replaced by x's text, recursively and each file once (GLSL has no
// includes). Empty, with `error` set, when a file is missing.
QByteArray assembleShader(const QString& file, const std::string& extraDefines, std::string* error);

// The GLSL #defines of the texture units (texture_units.h): TEXTURE_UNIT_CHAIN and so on.
std::string textureUnitDefines();

// A linked program of two shader files, its sampler uniforms set to their units (kSamplerUnits);
// null with `error` set when a file is missing or does not compile or link.
std::unique_ptr<QOpenGLShaderProgram> buildProgram(const QString& vertexFile, const QString& fragmentFile,
                                                   std::string* error, const std::string& extraDefines = "");

}  // namespace mipgloss::ui
