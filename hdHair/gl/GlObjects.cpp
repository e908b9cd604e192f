#include "hdHair/gl/GlObjects.h"

#include <stdexcept>

#include "hdHair/gl/GpuMemory.h"
#include "hdHair/gl/ShaderSources.h"

namespace hdhair::gl {

void deleteBuffer(GLuint name) {
    forgetBuffer(name);
    glDeleteBuffers(1, &name);
}
void deleteVertexArray(GLuint name) { glDeleteVertexArrays(1, &name); }
void deleteTexture(GLuint name) {
    forgetTexture(name);
    glDeleteTextures(1, &name);
}
void deleteFramebuffer(GLuint name) { glDeleteFramebuffers(1, &name); }
void deleteProgram(GLuint name) { glDeleteProgram(name); }
void deleteQuery(GLuint name) { glDeleteQueries(1, &name); }

Buffer createBuffer(const void* data, size_t bytes, GLbitfield flags, const char* use) {
    GLuint name = 0;
    glCreateBuffers(1, &name);
    // glNamedBufferStorage rejects size 0; an empty buffer still gets a name.
    glNamedBufferStorage(name, static_cast<GLsizeiptr>(bytes ? bytes : 1), bytes ? data : nullptr, flags);
    checkGlError("creating a buffer");
    recordBufferBytes(name, bytes ? bytes : 1, use);
    return Buffer(name);
}

VertexArray createVertexArray() {
    GLuint name = 0;
    glCreateVertexArrays(1, &name);
    return VertexArray(name);
}

namespace {

GLenum stageOf(const std::string& name) {
    auto endsWith = [&](const char* suffix) {
        std::string s(suffix);
        return name.size() >= s.size() && name.compare(name.size() - s.size(), s.size(), s) == 0;
    };
    if (endsWith(".vert")) return GL_VERTEX_SHADER;
    if (endsWith(".tesc")) return GL_TESS_CONTROL_SHADER;
    if (endsWith(".tese")) return GL_TESS_EVALUATION_SHADER;
    if (endsWith(".geom")) return GL_GEOMETRY_SHADER;
    if (endsWith(".frag")) return GL_FRAGMENT_SHADER;
    if (endsWith(".comp")) return GL_COMPUTE_SHADER;
    throw std::runtime_error("shader '" + name + "' has no known stage extension");
}

// The info log of a shader (glGetShaderiv, glGetShaderInfoLog) or a program
// (glGetProgramiv, glGetProgramInfoLog): the two pairs share their signatures.
std::string infoLog(GLuint object, PFNGLGETSHADERIVPROC getObjectiv,
                    PFNGLGETSHADERINFOLOGPROC getInfoLog) {
    GLint length = 0;
    getObjectiv(object, GL_INFO_LOG_LENGTH, &length);
    std::string log(static_cast<size_t>(length > 0 ? length : 1), '\0');
    getInfoLog(object, length, nullptr, log.data());
    return log.c_str();
}

}  // namespace

Program createProgram(const std::vector<std::string>& shaderNames,
                      const std::map<std::string, std::string>& overrides,
                      const std::vector<std::string>& captured) {
    Program program(glCreateProgram());
    std::vector<GLuint> shaders;
    auto release = [&] {
        for (GLuint shader : shaders) glDeleteShader(shader);
    };
    for (const std::string& name : shaderNames) {
        std::string source = expandedShaderSource(name, overrides);
        GLuint shader = glCreateShader(stageOf(name));
        shaders.push_back(shader);
        const char* text = source.c_str();
        glShaderSource(shader, 1, &text, nullptr);
        glCompileShader(shader);
        GLint compiled = GL_FALSE;
        glGetShaderiv(shader, GL_COMPILE_STATUS, &compiled);
        if (!compiled) {
            std::string log = infoLog(shader, glGetShaderiv, glGetShaderInfoLog);
            release();
            throw std::runtime_error("shaders/" + name + " does not compile:\n" + log);
        }
        glAttachShader(program.get(), shader);
    }
    if (!captured.empty()) {
        std::vector<const char*> names;
        for (const std::string& name : captured) names.push_back(name.c_str());
        glTransformFeedbackVaryings(program.get(), GLsizei(names.size()), names.data(), GL_INTERLEAVED_ATTRIBS);
    }
    glLinkProgram(program.get());
    release();
    GLint linked = GL_FALSE;
    glGetProgramiv(program.get(), GL_LINK_STATUS, &linked);
    if (!linked) {
        std::string names;
        for (const std::string& name : shaderNames) names += (names.empty() ? "" : ", ") + name;
        throw std::runtime_error("shader program (" + names + ") does not link:\n" +
                                 infoLog(program.get(), glGetProgramiv, glGetProgramInfoLog));
    }
    return program;
}

void checkGlError(const char* what) {
    GLenum error = glGetError();
    if (error == GL_NO_ERROR) return;
    const char* name = "unknown GL error";
    switch (error) {
    case GL_INVALID_ENUM: name = "GL_INVALID_ENUM"; break;
    case GL_INVALID_VALUE: name = "GL_INVALID_VALUE"; break;
    case GL_INVALID_OPERATION: name = "GL_INVALID_OPERATION"; break;
    case GL_OUT_OF_MEMORY: name = "GL_OUT_OF_MEMORY"; break;
    case GL_INVALID_FRAMEBUFFER_OPERATION: name = "GL_INVALID_FRAMEBUFFER_OPERATION"; break;
    default: break;
    }
    while (glGetError() != GL_NO_ERROR) {
    }
    // Running out of memory is the one error a user can act on (a smaller
    // image, fewer or smaller shadow maps, a smaller exactMemoryMB), so it
    // says so in words; the others are hdHair's bugs and name the GL enum.
    if (error == GL_OUT_OF_MEMORY)
        throw std::runtime_error(std::string("the GL driver is out of memory (GL_OUT_OF_MEMORY) while ") + what +
                                 "; use a smaller image, shadowMapResolution or exactMemoryMB");
    throw std::runtime_error(std::string(name) + " while " + what);
}

}  // namespace hdhair::gl
