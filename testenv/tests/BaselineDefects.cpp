#include "BaselineDefects.h"

#include <algorithm>
#include <cmath>
#include <sstream>

#include <glm/common.hpp>
#include <glm/geometric.hpp>
#include <glm/matrix.hpp>

#include "hdHair/curves/CatmullRomEvaluation.h"
#include "hdHair/curves/PreparedCurves.h"
#include "hdHair/curves/StrandColorSource.h"

namespace hdhair::testenv {
namespace {

std::string number(double value) {
    std::ostringstream text;
    text << value;
    return text.str();
}

struct VisiblePrim {
    const CurvesPrim* prim;
    PreparedCurves prepared;  // world space, Catmull-Rom control points, colours as drawn
};

std::vector<VisiblePrim> visiblePrims(const Scene& scene) {
    std::vector<VisiblePrim> prims;
    Diagnostics ignored;  // the baseline render reports the stage's warnings
    for (const auto& [path, entry] : scene.curves()) {
        if (!entry.prim->visible) continue;
        const SceneEntry<MaterialPrim>* material = scene.findMaterial(entry.prim->materialBinding);
        StrandColorSource colors = strandColorSource(*entry.prim, material ? material->prim.get() : nullptr, ignored);
        prims.push_back({entry.prim.get(), prepareCurves(*entry.prim, ignored, {}, &colors)});
    }
    return prims;
}

// A strand as drawn, cut into short straight pieces on screen: the
// Catmull-Rom span sampled at kPiecesPerSpan + 1 points, with its width in
// pixels (blended strands are drawn at least minPixelWidth wide).
constexpr int kPiecesPerSpan = 8;

struct ScreenPiece {
    glm::dvec2 a, b;
    double halfWidth;
    size_t strand;  // distinct for every curve of every prim
};

double distanceBetween(const ScreenPiece& p, const ScreenPiece& q) {
    // The closest points of two segments lie at an end point of one of them,
    // unless they cross.
    auto pointToSegment = [](glm::dvec2 point, glm::dvec2 a, glm::dvec2 b) {
        glm::dvec2 ab = b - a;
        double t = glm::dot(ab, ab) > 0.0 ? glm::clamp(glm::dot(point - a, ab) / glm::dot(ab, ab), 0.0, 1.0) : 0.0;
        return glm::length(point - (a + t * ab));
    };
    auto side = [](glm::dvec2 a, glm::dvec2 b, glm::dvec2 c) {
        return (b.x - a.x) * (c.y - a.y) - (b.y - a.y) * (c.x - a.x);
    };
    if (side(p.a, p.b, q.a) * side(p.a, p.b, q.b) < 0.0 && side(q.a, q.b, p.a) * side(q.a, q.b, p.b) < 0.0) return 0.0;
    return std::min({pointToSegment(p.a, q.a, q.b), pointToSegment(p.b, q.a, q.b), pointToSegment(q.a, p.a, p.b),
                     pointToSegment(q.b, p.a, p.b)});
}

// Two different strands cover the same pixels somewhere in the image: only
// there does the order they are blended in show.
bool strandsOverlapOnScreen(const std::vector<VisiblePrim>& prims, const CameraView& camera, double minPixelWidth) {
    const glm::dvec3 right = glm::normalize(glm::dvec3(glm::inverse(camera.view)[0]));
    std::vector<ScreenPiece> pieces;
    size_t firstStrand = 0;
    for (const VisiblePrim& visible : prims) {
        for (size_t s = 0; s < visible.prepared.segmentCount(); ++s) {
            glm::dvec3 previous(0.0);
            double previousHalfWidth = 0.0;
            for (int k = 0; k <= kPiecesPerSpan; ++k) {
                StrandControlPoint point = evaluate(visible.prepared.spanControls(s), float(k) / float(kPiecesPerSpan));
                glm::dvec3 position(point.position);
                glm::dvec3 pixel = camera.worldToPixel(position);
                double width = glm::length(glm::dvec2(camera.worldToPixel(position + right * double(point.width))) -
                                           glm::dvec2(pixel));
                double halfWidth = 0.5 * std::max(width, minPixelWidth);
                bool inFront = pixel.z >= 0.0 && pixel.z <= 1.0 && previous.z >= 0.0 && previous.z <= 1.0;
                if (k > 0 && inFront)
                    pieces.push_back({glm::dvec2(previous), glm::dvec2(pixel), std::max(halfWidth, previousHalfWidth),
                                      firstStrand + visible.prepared.segmentCurve[s]});
                previous = pixel;
                previousHalfWidth = halfWidth;
            }
        }
        firstStrand += visible.prepared.curveCount;
    }
    auto left = [](const ScreenPiece& p) { return std::min(p.a.x, p.b.x) - p.halfWidth; };
    auto rightEdge = [](const ScreenPiece& p) { return std::max(p.a.x, p.b.x) + p.halfWidth; };
    std::sort(pieces.begin(), pieces.end(),
              [&](const ScreenPiece& p, const ScreenPiece& q) { return left(p) < left(q); });
    for (size_t i = 0; i < pieces.size(); ++i)
        for (size_t j = i + 1; j < pieces.size() && left(pieces[j]) < rightEdge(pieces[i]); ++j)
            if (pieces[j].strand != pieces[i].strand &&
                distanceBetween(pieces[i], pieces[j]) < pieces[i].halfWidth + pieces[j].halfWidth)
                return true;
    return false;
}

// Second differences of four values along a span: zero when they change
// linearly, which tessellation reproduces at any level.
template <typename Vector>
bool variesNonlinearly(const Vector& a, const Vector& b, const Vector& c, const Vector& d) {
    double scale = std::max({double(glm::length(a)), double(glm::length(b)), double(glm::length(c)),
                             double(glm::length(d)), 1e-30});
    return double(glm::length(a - 2.0f * b + c)) > 1e-5 * scale || double(glm::length(b - 2.0f * c + d)) > 1e-5 * scale;
}

bool spanBends(const glm::vec3& p0, const glm::vec3& p1, const glm::vec3& p2, const glm::vec3& p3) {
    glm::dvec3 chord = glm::dvec3(p2) - glm::dvec3(p1);
    double length = glm::length(chord);
    if (length == 0.0) return false;
    for (const glm::vec3& p : {p0, p3})
        if (glm::length(glm::cross(glm::dvec3(p) - glm::dvec3(p1), chord)) / length > 1e-4 * length) return true;
    return false;
}

// Some span shows its tessellation: it bends, or its width, colour or
// opacity varies other than linearly along it.
bool tessellationShows(const std::vector<VisiblePrim>& prims) {
    for (const VisiblePrim& visible : prims) {
        for (size_t s = 0; s < visible.prepared.segmentCount(); ++s) {
            const StrandControlPoint* p = visible.prepared.spanControls(s);
            auto widthAndOpacity = [](const StrandControlPoint& point) {
                return glm::vec2(point.width, point.opacity);
            };
            if (spanBends(p[0].position, p[1].position, p[2].position, p[3].position) ||
                variesNonlinearly(widthAndOpacity(p[0]), widthAndOpacity(p[1]), widthAndOpacity(p[2]),
                                  widthAndOpacity(p[3])) ||
                variesNonlinearly(p[0].color, p[1].color, p[2].color, p[3].color))
                return true;
        }
    }
    return false;
}

BaselineDefect settingsDefect(std::string name, std::vector<std::string> settings) {
    BaselineDefect defect;
    defect.name = std::move(name);
    defect.settings = std::move(settings);
    return defect;
}

std::string shadingModelOf(const CurvesPrim& prim, const RenderSettings& settings) {
    return prim.shadingModel.empty() ? settings.getToken("shadingModel") : prim.shadingModel;
}

}  // namespace

std::vector<BaselineDefect> defectsThatApply(const Scene& scene, const StageRenderRequest& baseline,
                                             const RenderPlan& baselinePlan, const CameraView& camera) {
    const RenderSettings settings = stageSettings(baseline);
    const std::vector<VisiblePrim> prims = visiblePrims(scene);
    std::vector<BaselineDefect> defects;

    if (baselinePlan.recipe().transparency.path == TransparencyPath::BinSorted &&
        strandsOverlapOnScreen(prims, camera, settings.getFloat("minPixelWidth"))) {
        defects.push_back(settingsDefect("sorting off (transparency=unsorted)", {"transparency=unsorted"}));
    }

    auto kajiyaKayWithout = [&](const std::string& parameter) {
        return std::any_of(prims.begin(), prims.end(), [&](const VisiblePrim& visible) {
            return shadingModelOf(*visible.prim, settings) == "kajiyaKay" &&
                   !visible.prim->findPrimvar("hdHair:kajiyaKay:" + parameter);
        });
    };
    const double kd = settings.getFloat("kajiyaKay:diffuse"), ks = settings.getFloat("kajiyaKay:specular"),
                 shininess = settings.getFloat("kajiyaKay:shininess");
    if (kajiyaKayWithout("diffuse"))
        defects.push_back(settingsDefect("Kd " + number(kd) + " -> " + number(0.9 * kd),
                                         {"kajiyaKay:diffuse=" + number(0.9 * kd)}));
    if (kajiyaKayWithout("specular"))
        defects.push_back(settingsDefect("Ks " + number(ks) + " -> " + number(1.43 * ks),
                                         {"kajiyaKay:specular=" + number(1.43 * ks)}));
    if (kajiyaKayWithout("shininess"))
        defects.push_back(settingsDefect("shininess " + number(shininess) + " -> " + number(0.5 * shininess),
                                         {"kajiyaKay:shininess=" + number(0.5 * shininess)}));

    if (baseline.complexity != Complexity::Low && tessellationShows(prims)) {
        BaselineDefect coarser;
        coarser.name = std::string("complexity ") + toString(baseline.complexity) + " -> " +
                       toString(Complexity(int(baseline.complexity) - 1));
        coarser.complexityOneLevelLower = true;
        defects.push_back(coarser);
    }

    bool anyLit = std::any_of(prims.begin(), prims.end(), [&](const VisiblePrim& visible) {
        return shadingModelOf(*visible.prim, settings) != "flat";
    });
    for (const auto& [path, entry] : scene.lights())
        if (anyLit && entry.prim->visible && !entry.prim->hostCameraLight) {
            BaselineDefect dropped;
            dropped.name = "without the light " + path;
            dropped.removedLight = path;
            defects.push_back(dropped);
        }
    return defects;
}

DefectiveStage withDefect(const Scene& scene, const StageRenderRequest& baseline, const BaselineDefect& defect) {
    DefectiveStage stage{scene, baseline};
    stage.request.settings.insert(stage.request.settings.end(), defect.settings.begin(), defect.settings.end());
    if (defect.complexityOneLevelLower) stage.request.complexity = Complexity(int(baseline.complexity) - 1);
    if (!defect.removedLight.empty()) stage.scene.remove(defect.removedLight);
    return stage;
}

}  // namespace hdhair::testenv
