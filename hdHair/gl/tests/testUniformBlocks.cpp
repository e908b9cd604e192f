// The C++ copies of the shaders' blocks (hdHair/gl/UniformBlocks.h) against
// the layout the GL driver gives the linked programs: every member's offset,
// array and matrix strides, and the block's size. A field added, moved or
// resized on one side only fails here, by name, instead of shading with the
// wrong numbers.

#include <cstddef>
#include <set>
#include <string>
#include <vector>

#include <glad/gl.h>
#include <gtest/gtest.h>

#include "hdHair/gl/GlObjects.h"
#include "hdHair/gl/GlRenderThread.h"
#include "hdHair/gl/UniformBlocks.h"

using namespace hdhair::gl;

namespace {

// One member as C++ lays it out. Arrays and matrices give their stride.
struct Field {
    std::string name;  // as GL names it: "viewProjection", "lightVector[0]"
    size_t offset;
    size_t arrayStride = 0;   // 0: not an array
    int arraySize = 1;
    size_t matrixStride = 0;  // 0: not a matrix
};

constexpr size_t kVec4 = sizeof(glm::vec4);

struct Block {
    GLenum blockInterface;     // GL_UNIFORM_BLOCK or GL_SHADER_STORAGE_BLOCK
    GLenum variableInterface;  // GL_UNIFORM or GL_BUFFER_VARIABLE
    std::string name;
    std::string prefix;  // what GL puts before a member's name
    size_t size;         // sizeof the C++ struct (one element, for an array of structs)
    bool arrayOfStructs = false;
    std::vector<Field> fields;
};

const std::vector<Block>& blocks() {
    static const std::vector<Block> list = {
        {GL_UNIFORM_BLOCK, GL_UNIFORM, "FrameUniforms", "FrameUniforms.", sizeof(FrameUniforms), false,
         {
             {"viewProjection", offsetof(FrameUniforms, viewProjection), 0, 1, kVec4},  // column-major
             {"cameraPosition", offsetof(FrameUniforms, cameraPosition)},
             {"cameraForward", offsetof(FrameUniforms, cameraForward)},
             {"viewportSize", offsetof(FrameUniforms, viewportSize)},
             {"pixelsPerSegment", offsetof(FrameUniforms, pixelsPerSegment)},
             {"maxSegmentsPerSpan", offsetof(FrameUniforms, maxSegmentsPerSpan)},
             {"pixelsPerUnit", offsetof(FrameUniforms, pixelsPerUnit)},
             {"minPixelWidth", offsetof(FrameUniforms, minPixelWidth)},
             {"drawMode", offsetof(FrameUniforms, drawMode)},
             {"orderedDraw", offsetof(FrameUniforms, orderedDraw)},
             {"nearestStrandMinAlpha", offsetof(FrameUniforms, nearestStrandMinAlpha)},
             {"tessellationTolerance", offsetof(FrameUniforms, tessellationTolerance)},
             {"colorToRec709", offsetof(FrameUniforms, colorToRec709), 0, 1, kVec4},
             {"shadowSegmentLength", offsetof(FrameUniforms, shadowSegmentLength)},
         }},
        {GL_UNIFORM_BLOCK, GL_UNIFORM, "LightUniforms", "LightUniforms.", sizeof(LightUniforms), false,
         {
             {"lightVector[0]", offsetof(LightUniforms, lightVector), kVec4, kMaxLightsPerPass},
             {"lightScale[0]", offsetof(LightUniforms, lightScale), kVec4, kMaxLightsPerPass},
             {"lightAxis[0]", offsetof(LightUniforms, lightAxis), kVec4, kMaxLightsPerPass},
             {"lightCount", offsetof(LightUniforms, lightCount)},
             {"ambient", offsetof(LightUniforms, ambient)},
             {"lightCone[0]", offsetof(LightUniforms, lightCone), kVec4, kMaxLightsPerPass},
         }},
        {GL_UNIFORM_BLOCK, GL_UNIFORM, "ShadowUniforms", "ShadowUniforms.", sizeof(ShadowUniforms), false,
         {
             {"lightViewProjection[0]", offsetof(ShadowUniforms, lightViewProjection), 4 * kVec4, kMaxLightsPerPass,
              kVec4},
             {"lightEye[0]", offsetof(ShadowUniforms, lightEye), kVec4, kMaxLightsPerPass},
             {"lightForward[0]", offsetof(ShadowUniforms, lightForward), kVec4, kMaxLightsPerPass},
             {"lightMap[0]", offsetof(ShadowUniforms, lightMap), kVec4, kMaxLightsPerPass},
             {"layerBoundaries[0]", offsetof(ShadowUniforms, layerBoundaries), kVec4, kMaxShadowLayerVectors},
             {"mode", offsetof(ShadowUniforms, mode)},
             {"extinction", offsetof(ShadowUniforms, extinction)},
             {"occluders", offsetof(ShadowUniforms, occluders)},
             {"meshViewProjection[0]", offsetof(ShadowUniforms, meshViewProjection), 4 * kVec4, kMaxLightsPerPass,
              kVec4},
             {"meshEye[0]", offsetof(ShadowUniforms, meshEye), kVec4, kMaxLightsPerPass},
             {"meshForward[0]", offsetof(ShadowUniforms, meshForward), kVec4, kMaxLightsPerPass},
             {"meshMap[0]", offsetof(ShadowUniforms, meshMap), kVec4, kMaxLightsPerPass},
             {"volumeOrigin", offsetof(ShadowUniforms, volumeOrigin)},
             {"volume", offsetof(ShadowUniforms, volume)},
         }},
        // An unsized array of HairMaterial: each element laid out as GpuHairMaterial.
        {GL_SHADER_STORAGE_BLOCK, GL_BUFFER_VARIABLE, "HairMaterials", "materials[0].", sizeof(GpuHairMaterial), true,
         {
             {"modelAndLayer", offsetof(GpuHairMaterial, modelAndLayer)},
             {"segments", offsetof(GpuHairMaterial, segments)},
             {"kajiyaKay", offsetof(GpuHairMaterial, kajiyaKay)},
             {"alphaEta", offsetof(GpuHairMaterial, alphaEta)},
             {"betaGlint", offsetof(GpuHairMaterial, betaGlint)},
             {"sigmaA", offsetof(GpuHairMaterial, sigmaA)},
             {"caustic", offsetof(GpuHairMaterial, caustic)},
         }},
    };
    return list;
}

GLint resourceProperty(GLuint program, GLenum interface, GLuint index, GLenum property) {
    GLint value = -1;
    glGetProgramResourceiv(program, interface, index, 1, &property, 1, nullptr, &value);
    return value;
}

std::string resourceName(GLuint program, GLenum interface, GLuint index) {
    GLint length = resourceProperty(program, interface, index, GL_NAME_LENGTH);
    std::string name(size_t(std::max(length, 1)), '\0');
    glGetProgramResourceName(program, interface, index, length, nullptr, name.data());
    name.resize(name.find('\0'));
    return name;
}

// Checks every block of `blocks()` that `program` uses against its C++ copy;
// `found` counts the blocks the program has.
void expectBlocksMatch(GLuint program, const std::string& programName, int* found) {
    for (const Block& block : blocks()) {
        SCOPED_TRACE(programName + ": " + block.name);
        GLuint blockIndex = glGetProgramResourceIndex(program, block.blockInterface, block.name.c_str());
        if (blockIndex == GL_INVALID_INDEX) continue;
        ++*found;
        // The block's members as GL lists them, each of which C++ must know.
        std::set<std::string> members;
        GLint memberCount = resourceProperty(program, block.blockInterface, blockIndex, GL_NUM_ACTIVE_VARIABLES);
        std::vector<GLint> memberIndices(size_t(std::max(memberCount, 0)));
        const GLenum activeVariables = GL_ACTIVE_VARIABLES;
        glGetProgramResourceiv(program, block.blockInterface, blockIndex, 1, &activeVariables, memberCount, nullptr,
                               memberIndices.data());
        for (GLint index : memberIndices) members.insert(resourceName(program, block.variableInterface, GLuint(index)));
        std::set<std::string> known;
        for (const Field& field : block.fields) known.insert(block.prefix + field.name);
        EXPECT_EQ(members, known) << "the shader's members and UniformBlocks.h's differ";

        if (block.arrayOfStructs) {
            GLuint first = glGetProgramResourceIndex(program, block.variableInterface,
                                                     (block.prefix + block.fields.front().name).c_str());
            ASSERT_NE(first, GL_INVALID_INDEX);
            EXPECT_EQ(resourceProperty(program, block.variableInterface, first, GL_TOP_LEVEL_ARRAY_STRIDE),
                      GLint(block.size))
                << "element size";
        } else {
            EXPECT_EQ(resourceProperty(program, block.blockInterface, blockIndex, GL_BUFFER_DATA_SIZE),
                      GLint(block.size))
                << "block size";
        }
        for (const Field& field : block.fields) {
            SCOPED_TRACE(field.name);
            GLuint index =
                glGetProgramResourceIndex(program, block.variableInterface, (block.prefix + field.name).c_str());
            ASSERT_NE(index, GL_INVALID_INDEX) << "not in the shader";
            EXPECT_EQ(resourceProperty(program, block.variableInterface, index, GL_BLOCK_INDEX), GLint(blockIndex));
            EXPECT_EQ(resourceProperty(program, block.variableInterface, index, GL_OFFSET), GLint(field.offset));
            EXPECT_EQ(resourceProperty(program, block.variableInterface, index, GL_ARRAY_STRIDE),
                      GLint(field.arrayStride));
            EXPECT_EQ(resourceProperty(program, block.variableInterface, index, GL_MATRIX_STRIDE),
                      GLint(field.matrixStride));
            if (field.matrixStride) {
                EXPECT_EQ(resourceProperty(program, block.variableInterface, index, GL_IS_ROW_MAJOR), 0);
            }
            EXPECT_EQ(resourceProperty(program, block.variableInterface, index, GL_ARRAY_SIZE), field.arraySize);
        }
    }
}

}  // namespace

TEST(UniformBlocks, CopiesMatchTheLayoutGlGivesEveryProgram) {
    GlRenderThread thread(GlBackend::Egl);
    thread.run([] {
        // The programs the passes link (StrandPass, FragmentListPass,
        // ShadowMapPass, ShadowReferencePass) and how many of the blocks
        // each has: the shading programs all, the shadow builders the frame,
        // light and shadow blocks (they include lights.glsl for
        // HDHAIR_MAX_LIGHTS, and std140 blocks stay active unused).
        const std::vector<std::pair<std::string, int>> programs = {
            {"strand.frag", int(blocks().size())},
            {"strandFragmentList.frag", int(blocks().size())},
            {"shadowDepth.frag", 3},
            {"deepOpacity.frag", 3},
            {"shadowFragmentList.frag", 3},
        };
        for (const auto& [fragment, blockCount] : programs) {
            Program program = createProgram({"strand.vert", "strand.tesc", "strand.tese", "strand.geom", fragment});
            int found = 0;
            expectBlocksMatch(program.get(), fragment, &found);
            EXPECT_EQ(found, blockCount) << fragment << " uses the blocks it should";
        }
    });
}
