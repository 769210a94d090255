#include "shaders.h"

#include "texture_units.h"

#include "mipgloss/scene/lookup_plan.h"

#include <QFile>

#include <set>

namespace mipgloss::ui {

namespace {

const QString kShaderDir = QStringLiteral(":/mipgloss/shaders/");

// `file`'s text with its #include lines (at a line's start) resolved; files already in `included`
// become nothing. An included file's text starts at "#line 1" and the line after it is numbered as
// in the including file, so the compiler's line numbers are those of the file each line is in.
bool expandIncludes(const QString& file, std::set<QString>& included, QByteArray& text, std::string* error) {
    QFile source(kShaderDir + file);
    if (!source.open(QIODevice::ReadOnly)) {
        if (error) *error = "shader " + file.toStdString() + ": missing";
        return false;
    }
    included.insert(file);
    static constexpr char kInclude[] = "#include \"";
    const QList<QByteArray> lines = source.readAll().split('\n');
    text.clear();
    for (qsizetype i = 0; i < lines.size(); ++i) {
        const QByteArray& line = lines[i];
        if (i > 0) text += '\n';
        if (!line.startsWith(kInclude)) {  // only a line's start: comments may name an include
            text += line;
            continue;
        }
        const qsizetype nameStart = static_cast<qsizetype>(sizeof(kInclude) - 1);
        const qsizetype nameEnd = line.indexOf('"', nameStart);
        if (nameEnd < 0) {
            if (error) *error = "shader " + file.toStdString() + ": malformed #include";
            return false;
        }
        const QString name = QString::fromUtf8(line.mid(nameStart, nameEnd - nameStart));
        if (included.count(name)) continue;
        QByteArray inserted;
        if (!expandIncludes(name, included, inserted, error)) return false;
        text += "#line 1\n" + inserted + "\n#line " + QByteArray::number(i + 2);  // i + 2: the next line, 1-based
    }
    return true;
}

}  // namespace

std::string textureUnitDefines() {
    std::string text;
    auto define = [&](const char* name, GLuint unit) { text += "#define " + std::string(name) + " " + std::to_string(unit) + "\n"; };
    define("TEXTURE_UNIT_CHAIN", unitIndex(TextureUnit::Chain));
    define("TEXTURE_UNIT_PICTURE", unitIndex(TextureUnit::Picture));
    define("TEXTURE_UNIT_IRRADIANCE", unitIndex(TextureUnit::Irradiance));
    define("TEXTURE_UNIT_STACK", unitIndex(TextureUnit::Stack));
    define("TEXTURE_UNIT_SPLIT_SUM", unitIndex(TextureUnit::SplitSum));
    define("TEXTURE_UNIT_LOBE_MEAN", unitIndex(TextureUnit::LobeMean));
    define("TEXTURE_UNIT_FITTED_LOBES", unitIndex(TextureUnit::FittedLobes));
    define("TEXTURE_UNIT_COAT_CHAIN", unitIndex(TextureUnit::CoatChain));
    define("TEXTURE_UNIT_DIFFUSE_CHAIN", unitIndex(TextureUnit::DiffuseChain));
    define("TEXTURE_UNIT_FIRST_MAP", unitIndex(TextureUnit::FirstMap));
    return text;
}

QByteArray assembleShader(const QString& file, const std::string& extraDefines, std::string* error) {
    std::set<QString> included;
    QByteArray source;
    if (!expandIncludes(file, included, source, error)) return {};
    const qsizetype versionEnd = source.indexOf('\n') + 1;
    // #line keeps the compiler's line numbers those of the file.
    source.insert(versionEnd, QByteArray::fromStdString(shaderDefines() + textureUnitDefines() + extraDefines + "#line 2\n"));
    return source;
}

std::unique_ptr<QOpenGLShaderProgram> buildProgram(const QString& vertexFile, const QString& fragmentFile,
                                                   std::string* error, const std::string& extraDefines) {
    const QByteArray vertex = assembleShader(vertexFile, extraDefines, error);
    const QByteArray fragment = assembleShader(fragmentFile, extraDefines, error);
    if (vertex.isEmpty() || fragment.isEmpty()) return nullptr;
    auto program = std::make_unique<QOpenGLShaderProgram>();
    if (!program->addCacheableShaderFromSourceCode(QOpenGLShader::Vertex, vertex) ||
        !program->addCacheableShaderFromSourceCode(QOpenGLShader::Fragment, fragment) || !program->link()) {
        if (error) *error = "shader " + fragmentFile.toStdString() + ": " + program->log().toStdString();
        return nullptr;
    }
    program->bind();
    for (const SamplerUnit& s : kSamplerUnits)
        if (const int location = program->uniformLocation(s.uniform); location >= 0)
            program->setUniformValue(location, static_cast<GLint>(s.unit));
    program->release();
    return program;
}

}  // namespace mipgloss::ui
