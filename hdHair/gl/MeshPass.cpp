#include "hdHair/gl/MeshPass.h"

#include <glm/gtc/type_ptr.hpp>

namespace hdhair::gl {

namespace {

// Uniform locations (shaders/include/meshGeometry.glsl, shaders/mesh.frag).
constexpr GLint kViewProjection = 0, kPrimAndInstance = 1, kLit = 2;

}  // namespace

MeshPass::MeshPass()
    : shaded_(createProgram({"mesh.vert", "mesh.frag"})),
      lightDepth_(createProgram({"mesh.vert", "meshShadowDepth.frag"})),
      emptyVertexArray_(createVertexArray()) {
    checkGlError("setting up the mesh pass");
}

void MeshPass::draw(const MeshGeometry& geometry, const std::vector<MeshDraw>& draws, const glm::mat4& viewProjection,
                    MeshShading shading) {
    const GLuint program = shading == MeshShading::LightDepth ? lightDepth_.get() : shaded_.get();
    geometry.bind();
    glUseProgram(program);
    glProgramUniformMatrix4fv(program, kViewProjection, 1, GL_FALSE, glm::value_ptr(viewProjection));
    if (shading != MeshShading::LightDepth) glProgramUniform1i(program, kLit, shading == MeshShading::Lit ? 1 : 0);
    glBindVertexArray(emptyVertexArray_.get());
    if (shading == MeshShading::LightDepth) {
        // The least depth wins in any order; nothing is clipped at the light
        // view's near or far plane (fitted to the hair, not the meshes).
        glDisable(GL_DEPTH_TEST);
        glEnable(GL_BLEND);
        glBlendEquation(GL_MIN);
        glEnable(GL_DEPTH_CLAMP);
    } else {
        glEnable(GL_DEPTH_TEST);
        glDepthFunc(GL_LESS);
        glDepthMask(GL_TRUE);
        glDisable(GL_BLEND);
    }
    // Open meshes hide what is behind them from either side.
    glDisable(GL_CULL_FACE);
    for (const MeshDraw& mesh : draws) {
        if (mesh.count == 0) continue;
        if (shading != MeshShading::LightDepth)
            glProgramUniform2i(program, kPrimAndInstance, mesh.primAndInstance.x, mesh.primAndInstance.y);
        glDrawArrays(GL_TRIANGLES, GLint(mesh.first), GLsizei(mesh.count));
    }
    if (shading == MeshShading::LightDepth) {
        glBlendEquation(GL_FUNC_ADD);
        glDisable(GL_BLEND);
        glDisable(GL_DEPTH_CLAMP);
    }
    glBindVertexArray(0);
    glUseProgram(0);
    checkGlError("drawing meshes");
}

}  // namespace hdhair::gl
