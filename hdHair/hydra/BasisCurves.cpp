#include "hdHair/hydra/BasisCurves.h"

#include "pxr/base/tf/diagnostic.h"
#include "pxr/imaging/hd/basisCurvesTopology.h"
#include "pxr/imaging/hd/changeTracker.h"
#include "pxr/imaging/hd/sceneDelegate.h"
#include "pxr/imaging/hd/tokens.h"

#include "hdHair/hydra/HydraCamera.h"
#include "hdHair/hydra/RenderParam.h"
#include "hdHair/hydra/RprimSync.h"

PXR_NAMESPACE_OPEN_SCOPE

namespace {

// Topology indices make vertex-rate data indirect (HdBasisCurvesTopology's
// curveIndices); the engine wants one element per curve vertex.
template <typename T>
std::vector<T> expandThroughIndices(std::vector<T> const& data, std::vector<int> const& indices, size_t tuple) {
    std::vector<T> out;
    out.reserve(indices.size() * tuple);
    for (int index : indices) {
        size_t start = size_t(index) * tuple;
        for (size_t c = 0; c < tuple; ++c) out.push_back(start + c < data.size() ? data[start + c] : T{});
    }
    return out;
}

}  // namespace

HdHairBasisCurves::HdHairBasisCurves(SdfPath const& id) : HdBasisCurves(id) { _curves.path = id.GetString(); }

HdDirtyBits HdHairBasisCurves::GetInitialDirtyBitsMask() const {
    return HdChangeTracker::Clean | HdChangeTracker::InitRepr | HdChangeTracker::DirtyPoints |
           HdChangeTracker::DirtyTopology | HdChangeTracker::DirtyTransform | HdChangeTracker::DirtyVisibility |
           HdChangeTracker::DirtyWidths | HdChangeTracker::DirtyNormals | HdChangeTracker::DirtyPrimvar |
           HdChangeTracker::DirtyInstancer | HdChangeTracker::DirtyInstanceIndex | HdChangeTracker::DirtyMaterialId |
           HdChangeTracker::DirtyDisplayStyle | HdChangeTracker::DirtyExtent | HdChangeTracker::DirtyPrimID;
}

HdDirtyBits HdHairBasisCurves::_PropagateDirtyBits(HdDirtyBits bits) const {
    // The base class adds points, normals and primvars on a topology change,
    // but not widths, whose count depends on the topology too.
    if (bits & HdChangeTracker::DirtyTopology) bits |= HdChangeTracker::DirtyWidths;
    return bits;
}

void HdHairBasisCurves::_InitRepr(TfToken const& reprToken, HdDirtyBits*) {
    // hdHair draws every repr the same way; Hydra only needs it recorded.
    auto found = std::find_if(_reprs.begin(), _reprs.end(), _ReprComparator(reprToken));
    if (found == _reprs.end()) _reprs.emplace_back(reprToken, HdReprSharedPtr());
}

void HdHairBasisCurves::Sync(HdSceneDelegate* sceneDelegate, HdRenderParam* renderParam, HdDirtyBits* dirtyBits,
                             TfToken const&) {
    auto* param = static_cast<HdHairRenderParam*>(renderParam);
    SdfPath const& id = GetId();
    HdDirtyBits bits = *dirtyBits;

    if (HdChangeTracker::IsVisibilityDirty(bits, id)) _UpdateVisibility(sceneDelegate, dirtyBits);
    _curves.visible = IsVisible();
    if (HdChangeTracker::IsPrimIdDirty(bits, id) || _curves.primId < 0) _curves.primId = GetPrimId();
    if (HdChangeTracker::IsTransformDirty(bits, id)) {
        _primTransform = sceneDelegate->GetTransform(id);
        _curves.worldTransform = hdhair::hydra::matrixFromGf(_primTransform.data());
    }
    _SyncInstances(sceneDelegate, dirtyBits);
    if (HdChangeTracker::IsDisplayStyleDirty(bits, id)) _refineLevel = GetDisplayStyle(sceneDelegate).refineLevel;
    if (HdChangeTracker::IsTopologyDirty(bits, id)) _SyncTopology(sceneDelegate);
    if (HdChangeTracker::IsAnyPrimvarDirty(bits, id)) _SyncPrimvars(sceneDelegate, bits);
    if (bits & HdChangeTracker::DirtyMaterialId) {
        SetMaterialId(sceneDelegate->GetMaterialId(id));
        _curves.materialBinding = GetMaterialId().GetString();
    }

    param->SetCurves(this, _curves, _refineLevel, _instanceTransforms);
    *dirtyBits &= ~HdChangeTracker::AllSceneDirtyBits;
}

void HdHairBasisCurves::_SyncTopology(HdSceneDelegate* sceneDelegate) {
    HdBasisCurvesTopology topology = GetBasisCurvesTopology(sceneDelegate);
    // Hd's tokens are spelled as USD's; Hd-only ones (segmented wrap,
    // centripetalCatmullRom, hermite, power) fall back with a warning.
    if (!hdhair::parseToken(topology.GetCurveType().GetString(), &_curves.type)) _curves.type =
        hdhair::CurveType::Cubic;
    if (_curves.type == hdhair::CurveType::Cubic &&
        !hdhair::parseToken(topology.GetCurveBasis().GetString(), &_curves.basis)) {
        TF_WARN("hdHair: %s: curve basis '%s' is not supported; drawn as catmullRom", GetId().GetText(),
                topology.GetCurveBasis().GetText());
        _curves.basis = hdhair::CurveBasis::CatmullRom;
    }
    if (!hdhair::parseToken(topology.GetCurveWrap().GetString(), &_curves.wrap)) {
        TF_WARN("hdHair: %s: curve wrap '%s' is not supported; drawn as nonperiodic", GetId().GetText(),
                topology.GetCurveWrap().GetText());
        _curves.wrap = hdhair::CurveWrap::Nonperiodic;
    }
    VtIntArray const& counts = topology.GetCurveVertexCounts();
    _curves.curveVertexCounts.assign(counts.begin(), counts.end());
    VtIntArray const& indices = topology.GetCurveIndices();
    _curveIndices.assign(indices.begin(), indices.end());
    // Storm hides invisible curves and, for curves, ignores invisible
    // points (they only hide points in its points repr); so does hdHair.
    VtIntArray const& invisible = topology.GetInvisibleCurves();
    _curves.invisibleCurves.assign(invisible.begin(), invisible.end());
}

void HdHairBasisCurves::_SyncInstances(HdSceneDelegate* sceneDelegate, HdDirtyBits* dirtyBits) {
    HdDirtyBits const bits = *dirtyBits;
    _UpdateInstancer(sceneDelegate, dirtyBits);
    HdHairSyncInstanceTransforms(sceneDelegate, GetId(), GetInstancerId(), bits, _primTransform, _instanceTransforms);
}

void HdHairBasisCurves::_SyncPrimvars(HdSceneDelegate* sceneDelegate, HdDirtyBits bits) {
    SdfPath const& id = GetId();
    std::set<std::string> const present = HdHairPullPrimvars(sceneDelegate, id, bits, [&](HdHairPulledPrimvar& pulled) {
        VtValue const& value = pulled.value;
        if (pulled.name == "hdHair:shadingModel") {
            // The one token primvar hdHair reads (HdHairAPI, constant only).
            _curves.shadingModel = value.IsHolding<TfToken>() ? value.UncheckedGet<TfToken>().GetString()
                                   : value.IsHolding<std::string>() ? value.UncheckedGet<std::string>()
                                   : value.IsHolding<VtTokenArray>() && value.UncheckedGet<VtTokenArray>().size() == 1
                                       ? value.UncheckedGet<VtTokenArray>()[0].GetString()
                                       : std::string();
            return;
        }
        hdhair::Primvar primvar;
        if (!HdHairToEnginePrimvar(pulled, &primvar)) {
            // Token and string primvars other than the shading model have no engine
            // counterpart: materials reach hdHair through their numeric primvars.
            _curves.primvars.erase(pulled.name);
            return;
        }
        if (pulled.name == HdTokens->points.GetString()) {
            if (primvar.tupleSize != 3) {
                TF_WARN("hdHair: %s.points: expected 3 components a point, got %s; prim not drawn", id.GetText(),
                        primvar.typeName.c_str());
                primvar.values.clear();
            }
            if (!_curveIndices.empty()) primvar.values = expandThroughIndices(primvar.values, _curveIndices, 3);
            _curves.points.resize(primvar.values.size() / 3);
            for (size_t p = 0; p < _curves.points.size(); ++p)
                _curves.points[p] =
                    glm::vec3(primvar.values[3 * p], primvar.values[3 * p + 1], primvar.values[3 * p + 2]);
            return;
        }
        if (!_curveIndices.empty() && primvar.interpolation == hdhair::Interpolation::Vertex && primvar.indices.empty())
            primvar.values = expandThroughIndices(primvar.values, _curveIndices, size_t(primvar.tupleSize));
        _curves.primvars[pulled.name] = std::move(primvar);
    });
    if (!present.count("hdHair:shadingModel")) _curves.shadingModel.clear();
    // Primvars that are gone (removed, or no longer in any descriptor).
    HdHairEraseMissingPrimvars(_curves.primvars, present);
}

void HdHairBasisCurves::Finalize(HdRenderParam* renderParam) {
    static_cast<HdHairRenderParam*>(renderParam)->Remove(GetId().GetString());
}

PXR_NAMESPACE_CLOSE_SCOPE
