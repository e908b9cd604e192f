// The screenError tessellation rule (shaders/strand.tesc) as the GPU runs it:
// the strand shaders draw with transform feedback, which records every
// vertex the tessellator made (the centre line under it, its parameter on
// the span and its segment), and the polylines are checked against the
// curve the prim describes, evaluated on the CPU by ReferenceCurveEvaluator
// and projected to pixels.

#include <algorithm>
#include <cmath>
#include <map>
#include <random>
#include <vector>

#include <glad/gl.h>
#include <glm/geometric.hpp>
#include <glm/gtc/matrix_transform.hpp>
#include <gtest/gtest.h>

#include "hdHair/base/Diagnostics.h"
#include "hdHair/curves/PreparedCurves.h"
#include "hdHair/curves/ReferenceCurveEvaluator.h"
#include "hdHair/gl/GlObjects.h"
#include "hdHair/gl/GlRenderThread.h"
#include "hdHair/gl/StrandGeometry.h"
#include "hdHair/gl/UniformBlocks.h"
#include "hdHair/plan/CameraView.h"
#include "hdHair/scene/CurvesPrim.h"

using namespace hdhair;

namespace {

// One recorded tessellator vertex, as strand.tese writes the captured outputs.
struct CapturedVertex {
    glm::vec3 centre;  // strandCentre
    float u;           // spanU
    glm::ivec4 ids;    // primId, elementId, material, segment
};
static_assert(sizeof(CapturedVertex) == 32, "interleaved vec3, float, ivec4");

// Curly Catmull-Rom strands: helices of random radius and pitch around
// random axes, some nearly straight, some tight, spread through `box`.
CurvesPrim curlyStrands(unsigned seed, int curves, float box) {
    std::mt19937 random(seed);
    std::uniform_real_distribution<float> unit(0.0f, 1.0f);
    CurvesPrim prim;
    prim.path = "/curls";
    prim.type = CurveType::Cubic;
    prim.basis = CurveBasis::CatmullRom;
    for (int c = 0; c < curves; ++c) {
        glm::vec3 start = (glm::vec3(unit(random), unit(random), unit(random)) - 0.5f) * box;
        glm::vec3 axis = glm::normalize(glm::vec3(unit(random), unit(random), unit(random)) - 0.5f);
        glm::vec3 side = glm::normalize(glm::cross(axis, std::abs(axis.x) < 0.9f ? glm::vec3(1, 0, 0) : glm::vec3(0, 1, 0)));
        glm::vec3 other = glm::cross(axis, side);
        float radius = 0.01f + 0.2f * unit(random) * unit(random), pitch = 0.02f + 0.2f * unit(random);
        float step = 0.3f + 1.2f * unit(random);  // radians between vertices: up to a very coarse curl
        const int vertices = 8;
        prim.curveVertexCounts.push_back(vertices);
        for (int v = 0; v < vertices; ++v) {
            float angle = step * float(v);
            prim.points.push_back(start + axis * (pitch * float(v)) +
                                  radius * (std::cos(angle) * side + std::sin(angle) * other));
        }
    }
    Primvar widths;
    widths.name = "widths";
    widths.values = {0.001f};
    prim.primvars["widths"] = widths;
    return prim;
}

CameraView perspectiveCamera(const glm::dvec3& eye, int width) {
    CameraPrim camera;
    camera.focalLength = 20.0f;  // wide: about 55 degrees across
    camera.clippingRange = {0.01f, 100.0f};
    camera.worldTransform = glm::inverse(glm::lookAt(eye, glm::dvec3(0.0), glm::dvec3(0, 1, 0)));
    return cameraViewFromPrim(camera, width);
}

CameraView orthographicCamera(int width) {
    CameraPrim camera;
    camera.projection = Projection::Orthographic;
    camera.horizontalAperture = camera.verticalAperture = 30.0f;  // 3 units across
    camera.worldTransform = glm::translate(glm::dmat4(1.0), glm::dvec3(0.0, 0.0, 5.0));
    return cameraViewFromPrim(camera, width);
}

// Every vertex the strand shaders' tessellator makes for `curves` seen by
// `camera` with screenError tessellation at `tolerance` pixels.
std::vector<CapturedVertex> tessellate(const PreparedCurves& curves, const CameraView& camera, float tolerance,
                                       int maxSegmentsPerSpan) {
    gl::GlRenderThread thread(gl::GlBackend::Egl);
    return thread.run([&] {
        gl::Program program = gl::createProgram({"strand.vert", "strand.tesc", "strand.tese", "strand.geom"}, {},
                                                {"strandCentre", "spanU", "ids"});
        gl::StrandGeometry geometry;
        geometry.reserve(curves.segmentCount(), curves.controlPoints.size());
        geometry.write(0, 0, curves, 0);
        geometry.setBatching(gl::PatchBatching::forDriver(reinterpret_cast<const char*>(glGetString(GL_RENDERER))));
        geometry.bind();
        gl::Buffer order = gl::createBuffer(nullptr, sizeof(uint32_t), GL_DYNAMIC_STORAGE_BIT);
        glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 4, order.get());

        gl::FrameUniforms frame;
        frame.viewProjection = glm::mat4(camera.projection * camera.view);
        frame.viewportSize = glm::vec2(camera.imageWidth, camera.imageHeight);
        frame.cameraPosition = glm::vec4(glm::vec3(camera.position()), camera.orthographic ? 0.0f : 1.0f);
        frame.cameraForward = glm::vec4(glm::vec3(camera.forward()), 0.0f);
        frame.pixelsPerUnit = float(camera.pixelsPerUnit());
        frame.maxSegmentsPerSpan = float(maxSegmentsPerSpan);
        frame.tessellationTolerance = tolerance;
        gl::Buffer frameBlock = gl::createBuffer(&frame, sizeof(frame));
        glBindBufferBase(GL_UNIFORM_BUFFER, 0, frameBlock.get());

        // Two triangles a segment, three vertices each, at most.
        const size_t most = curves.segmentCount() * size_t(maxSegmentsPerSpan) * 6;
        gl::Buffer captured = gl::createBuffer(nullptr, most * sizeof(CapturedVertex), GL_MAP_READ_BIT);
        glBindBufferBase(GL_TRANSFORM_FEEDBACK_BUFFER, 0, captured.get());
        GLuint written = 0;
        glGenQueries(1, &written);
        // Nothing is rasterised, but a draw needs a complete framebuffer:
        // a surfaceless context has none, so one without attachments.
        GLuint framebuffer = 0;
        glCreateFramebuffers(1, &framebuffer);
        gl::Framebuffer framebufferName(framebuffer);
        glNamedFramebufferParameteri(framebuffer, GL_FRAMEBUFFER_DEFAULT_WIDTH, 1);
        glNamedFramebufferParameteri(framebuffer, GL_FRAMEBUFFER_DEFAULT_HEIGHT, 1);
        glBindFramebuffer(GL_FRAMEBUFFER, framebuffer);
        gl::VertexArray vertexArray = gl::createVertexArray();
        glUseProgram(program.get());
        glBindVertexArray(vertexArray.get());
        glEnable(GL_RASTERIZER_DISCARD);
        glBeginQuery(GL_TRANSFORM_FEEDBACK_PRIMITIVES_WRITTEN, written);
        glBeginTransformFeedback(GL_TRIANGLES);
        geometry.drawPatches({gl::SegmentRange{0, curves.segmentCount()}}, float(maxSegmentsPerSpan));
        glEndTransformFeedback();
        glEndQuery(GL_TRANSFORM_FEEDBACK_PRIMITIVES_WRITTEN);
        glDisable(GL_RASTERIZER_DISCARD);
        GLuint triangles = 0;
        glGetQueryObjectuiv(written, GL_QUERY_RESULT, &triangles);
        glDeleteQueries(1, &written);
        std::vector<CapturedVertex> vertices(size_t(triangles) * 3);
        glGetNamedBufferSubData(captured.get(), 0, GLsizeiptr(vertices.size() * sizeof(CapturedVertex)),
                                vertices.data());
        gl::checkGlError("capturing the tessellation");
        return vertices;
    });
}

glm::dvec2 pixelOf(const CameraView& camera, const glm::dvec3& world) { return glm::dvec2(camera.worldToPixel(world)); }

double distanceToSegment(const glm::dvec2& p, const glm::dvec2& a, const glm::dvec2& b) {
    glm::dvec2 ab = b - a;
    double t = glm::dot(ab, ab) > 0.0 ? std::clamp(glm::dot(p - a, ab) / glm::dot(ab, ab), 0.0, 1.0) : 0.0;
    return glm::length(p - (a + t * ab));
}

struct PolylineCheck {
    double largestError = 0.0;  // pixels, over every span
    size_t spans = 0, segments = 0;
    int mostSegments = 0;
};

// Groups the captured vertices by segment and measures, on each span, how far
// the true projected curve strays from the projected polyline the GPU made.
PolylineCheck checkPolylines(const CurvesPrim& prim, const PreparedCurves& curves, const CameraView& camera,
                             const std::vector<CapturedVertex>& vertices) {
    ReferenceCurveEvaluator reference(prim);
    std::vector<std::pair<size_t, int>> spanOf;  // segment -> (curve, span)
    for (size_t curve = 0; curve < reference.curveCount(); ++curve)
        for (int span = 0; span < reference.spanCount(curve); ++span) spanOf.emplace_back(curve, span);
    EXPECT_EQ(spanOf.size(), curves.segmentCount());

    std::map<int, std::map<float, glm::dvec3>> polylines;  // segment -> u -> centre
    for (const CapturedVertex& vertex : vertices) polylines[vertex.ids.w][vertex.u] = glm::dvec3(vertex.centre);
    PolylineCheck check;
    for (const auto& [segment, points] : polylines) {
        const auto [curve, span] = spanOf.at(size_t(segment));
        const int segments = int(points.size()) - 1;
        ++check.spans;
        check.segments += size_t(segments);
        check.mostSegments = std::max(check.mostSegments, segments);
        std::vector<float> us;
        std::vector<glm::dvec2> pixels;
        for (const auto& [u, centre] : points) {
            us.push_back(u);
            pixels.push_back(pixelOf(camera, centre));
            // The GPU's polyline vertices lie on the curve.
            EXPECT_LT(glm::length(centre - reference.position(curve, span, u)), 1e-4) << "segment " << segment;
        }
        for (int i = 0; i < segments; ++i) {
            for (int k = 1; k < 32; ++k) {
                double u = us[size_t(i)] + (us[size_t(i) + 1] - us[size_t(i)]) * k / 32.0;
                glm::dvec2 onCurve = pixelOf(camera, reference.position(curve, span, u));
                check.largestError = std::max(check.largestError,
                                              distanceToSegment(onCurve, pixels[size_t(i)], pixels[size_t(i) + 1]));
            }
        }
    }
    return check;
}

}  // namespace

class ScreenErrorTessellation : public ::testing::TestWithParam<double> {};

TEST_P(ScreenErrorTessellation, KeepsEveryPolylineWithinItsToleranceOfTheCurve) {
    const float tolerance = float(GetParam());
    CurvesPrim prim = curlyStrands(7, 300, 2.0f);
    Diagnostics diagnostics;
    PreparedCurves curves = prepareCurves(prim, diagnostics);
    ASSERT_TRUE(diagnostics.warnings().empty());
    for (const CameraView& camera : {perspectiveCamera({0.3, 0.2, 2.2}, 640), orthographicCamera(480)}) {
        std::vector<CapturedVertex> vertices = tessellate(curves, camera, tolerance, 64);
        PolylineCheck check = checkPolylines(prim, curves, camera, vertices);
        SCOPED_TRACE(camera.orthographic ? "orthographic" : "perspective");
        // Spans outside the view are culled; most are in it.
        EXPECT_GT(check.spans, curves.segmentCount() / 2);
        EXPECT_LT(check.mostSegments, 64) << "a span hit the cap: the tolerance was not what chose its level";
        // Within the tolerance (float positions: a thousandth of a pixel
        // of rounding), and not far within it: the bound is meant to be
        // close, so a rule that cut much finer than needed fails too.
        EXPECT_LE(check.largestError, tolerance * 1.001 + 1e-3);
        EXPECT_GT(check.largestError, 0.5 * tolerance);
    }
}

INSTANTIATE_TEST_SUITE_P(Tolerances, ScreenErrorTessellation, ::testing::Values(1.0, 0.25, 0.05));

TEST(ScreenErrorTessellationCost, AStraightSpanIsOneSegmentHoweverLongItLooks) {
    CurvesPrim prim;
    prim.path = "/straight";
    prim.type = CurveType::Cubic;
    prim.basis = CurveBasis::CatmullRom;
    prim.curveVertexCounts = {6};
    for (int i = 0; i < 6; ++i) prim.points.push_back({-1.4f + 0.56f * float(i), 0.1f * float(i) - 0.2f, 0.0f});
    Diagnostics diagnostics;
    PreparedCurves curves = prepareCurves(prim, diagnostics);
    CameraView camera = orthographicCamera(960);  // each span about 180 pixels long
    PolylineCheck check = checkPolylines(prim, curves, camera, tessellate(curves, camera, 0.01f, 64));
    EXPECT_EQ(check.spans, 3u);
    EXPECT_EQ(check.segments, 3u);
    EXPECT_LT(check.largestError, 1e-3);
}

TEST(ScreenErrorTessellationCost, TighterTolerancesCutFinerAsTheSquareRoot) {
    CurvesPrim prim = curlyStrands(11, 200, 2.0f);
    Diagnostics diagnostics;
    PreparedCurves curves = prepareCurves(prim, diagnostics);
    CameraView camera = orthographicCamera(480);
    size_t coarse = checkPolylines(prim, curves, camera, tessellate(curves, camera, 1.0f, 64)).segments;
    size_t fine = checkPolylines(prim, curves, camera, tessellate(curves, camera, 0.0625f, 64)).segments;
    // n grows as 1/sqrt(tolerance): 16 times tighter, about 4 times the
    // segments (spans at one segment already take fewer than 4 more).
    EXPECT_GT(double(fine), 2.5 * double(coarse));
    EXPECT_LT(double(fine), 4.5 * double(coarse));
}
