#include "hdHair/gl/DisplayTransformPass.h"

#include <algorithm>
#include <stdexcept>

#include "hdHair/gl/GpuMemory.h"

namespace hdhair::gl {

DisplayTransformPass::DisplayTransformPass() : emptyVertexArray_(createVertexArray()) {}

void DisplayTransformPass::build(const DisplayShader& shader) {
    if (program_ && shader.source == builtSource_) return;
    program_ = createProgram({"fullscreen.vert", "displayTransform.frag"},
                             {{"include/displayFunction.glsl", shader.source}});
    luts_.clear();
    GLint unit = 1;  // unit 0 is the frame's colour
    for (const DisplayShader::Texture& lut : shader.textures) {
        const bool volume = lut.depth > 0;
        const bool rows = !volume && lut.height > 1;
        GLuint name = 0;
        glCreateTextures(volume ? GL_TEXTURE_3D : rows ? GL_TEXTURE_2D : GL_TEXTURE_1D, 1, &name);
        Texture texture(name);
        const GLenum internal = lut.channels == 1 ? GL_R32F : GL_RGB32F;
        const GLenum format = lut.channels == 1 ? GL_RED : GL_RGB;
        if (volume) {
            glTextureStorage3D(name, 1, internal, GLsizei(lut.width), GLsizei(lut.height), GLsizei(lut.depth));
            recordTextureStorage(name, internal, GLsizei(lut.width), GLsizei(lut.height), GLsizei(lut.depth), 0,
                                 "displayTransform");
            glTextureSubImage3D(name, 0, 0, 0, 0, GLsizei(lut.width), GLsizei(lut.height), GLsizei(lut.depth), format,
                                GL_FLOAT, lut.values.data());
        } else if (rows) {
            glTextureStorage2D(name, 1, internal, GLsizei(lut.width), GLsizei(lut.height));
            recordTextureStorage(name, internal, GLsizei(lut.width), GLsizei(lut.height), 1, 0, "displayTransform");
            glTextureSubImage2D(name, 0, 0, 0, GLsizei(lut.width), GLsizei(lut.height), format, GL_FLOAT,
                                lut.values.data());
        } else {
            glTextureStorage1D(name, 1, internal, GLsizei(lut.width));
            recordTextureStorage(name, internal, GLsizei(lut.width), 1, 1, 0, "displayTransform");
            glTextureSubImage1D(name, 0, 0, GLsizei(lut.width), format, GL_FLOAT, lut.values.data());
        }
        const GLint filter = lut.linear ? GL_LINEAR : GL_NEAREST;
        glTextureParameteri(name, GL_TEXTURE_MIN_FILTER, filter);
        glTextureParameteri(name, GL_TEXTURE_MAG_FILTER, filter);
        for (GLenum wrap : {GL_TEXTURE_WRAP_S, GL_TEXTURE_WRAP_T, GL_TEXTURE_WRAP_R})
            glTextureParameteri(name, wrap, GL_CLAMP_TO_EDGE);
        glProgramUniform1i(program_.get(), glGetUniformLocation(program_.get(), lut.samplerName.c_str()), unit++);
        luts_.push_back(std::move(texture));
    }
    for (const DisplayShader::Uniform& uniform : shader.uniforms) {
        const GLint location = glGetUniformLocation(program_.get(), uniform.name.c_str());
        if (location < 0) continue;  // declared but optimised away
        std::vector<float> floats(uniform.values.begin(), uniform.values.end());
        std::vector<GLint> ints(uniform.values.begin(), uniform.values.end());
        using Kind = DisplayShader::Uniform::Kind;
        switch (uniform.kind) {
        case Kind::Float: glProgramUniform1f(program_.get(), location, floats[0]); break;
        case Kind::Bool: glProgramUniform1i(program_.get(), location, ints[0]); break;
        case Kind::Float3: glProgramUniform3fv(program_.get(), location, 1, floats.data()); break;
        case Kind::FloatArray: glProgramUniform1fv(program_.get(), location, GLsizei(floats.size()), floats.data()); break;
        case Kind::IntPairArray:
            glProgramUniform2iv(program_.get(), location, GLsizei(ints.size() / 2), ints.data());
            break;
        }
    }
    builtSource_ = shader.source;
    checkGlError("building the display transform");
}

std::vector<float> DisplayTransformPass::run(const DisplayShader& shader, GLuint linearColor, int width, int height,
                                             bool overBlack) {
    build(shader);
    if (width != width_ || height != height_) {
        GLuint name = 0;
        glCreateTextures(GL_TEXTURE_2D, 1, &name);
        target_ = Texture(name);
        glTextureStorage2D(name, 1, GL_RGBA32F, width, height);
        recordTextureStorage(name, GL_RGBA32F, width, height, 1, 0, "displayTransform");
        glCreateFramebuffers(1, &name);
        framebuffer_ = Framebuffer(name);
        glNamedFramebufferTexture(framebuffer_.get(), GL_COLOR_ATTACHMENT0, target_.get(), 0);
        width_ = width;
        height_ = height;
    }
    glBindFramebuffer(GL_FRAMEBUFFER, framebuffer_.get());
    glViewport(0, 0, width, height);
    glUseProgram(program_.get());
    glProgramUniform1i(program_.get(), glGetUniformLocation(program_.get(), "overBlack"), overBlack ? 1 : 0);
    glBindVertexArray(emptyVertexArray_.get());
    glBindTextureUnit(0, linearColor);
    for (size_t i = 0; i < luts_.size(); ++i) glBindTextureUnit(GLuint(i + 1), luts_[i].get());
    glDisable(GL_DEPTH_TEST);
    glDisable(GL_BLEND);
    glDrawArrays(GL_TRIANGLES, 0, 3);
    glEnable(GL_DEPTH_TEST);
    for (size_t i = 0; i <= luts_.size(); ++i) glBindTextureUnit(GLuint(i), 0);
    glBindVertexArray(0);
    glUseProgram(0);
    checkGlError("running the display transform");
    return readTopDown<float>(framebuffer_.get(), GL_COLOR_ATTACHMENT0, GL_RGBA, GL_FLOAT, 4, width, height);
}

}  // namespace hdhair::gl
