#include "hdHair/gl/MeshPass.h"

#include <glm/gtc/type_ptr.hpp>

namespace hdhair::gl {

namespace {

// Uniform locations (shaders/include/meshGeometry.glsl, shaders/mesh.frag).
constexpr GLint kViewProjection = 0, kPrimAndInstance = 1, kLit = 2;

}  // namespace

MeshPass::MeshPass()
    : shaded_(createProgram({"mesh.vert", "mesh.frag"})),
      // No fragment shader: the depth map of a light needs depth only.
      depthOnly_(createProgram({"mesh.vert"})),
      emptyVertexArray_(createVertexArray()) {
    checkGlError("setting up the mesh pass");
}

void MeshPass::draw(const MeshGeometry& geometry, const std::vector<MeshDraw>& draws, const glm::mat4& viewProjection,
                    MeshShading shading) {
    const GLuint program = shading == MeshShading::DepthOnly ? depthOnly_.get() : shaded_.get();
    geometry.bind();
    glUseProgram(program);
    glProgramUniformMatrix4fv(program, kViewProjection, 1, GL_FALSE, glm::value_ptr(viewProjection));
    if (shading != MeshShading::DepthOnly) glProgramUniform1i(program, kLit, shading == MeshShading::Lit ? 1 : 0);
    glBindVertexArray(emptyVertexArray_.get());
    glEnable(GL_DEPTH_TEST);
    glDepthFunc(GL_LESS);
    glDepthMask(GL_TRUE);
    glDisable(GL_BLEND);
    // Open meshes hide what is behind them from either side.
    glDisable(GL_CULL_FACE);
    if (shading == MeshShading::DepthOnly) glColorMask(GL_FALSE, GL_FALSE, GL_FALSE, GL_FALSE);
    for (const MeshDraw& mesh : draws) {
        if (mesh.count == 0) continue;
        if (shading != MeshShading::DepthOnly)
            glProgramUniform2i(program, kPrimAndInstance, mesh.primAndInstance.x, mesh.primAndInstance.y);
        glDrawArrays(GL_TRIANGLES, GLint(mesh.first), GLsizei(mesh.count));
    }
    glColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
    glBindVertexArray(0);
    glUseProgram(0);
    checkGlError("drawing meshes");
}

}  // namespace hdhair::gl
