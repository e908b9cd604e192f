#include "hdHair/render/FramePasses.h"

#include <algorithm>
#include <stdexcept>
#include <string>
#include <utility>

#include <fmt/format.h>
#include <glad/gl.h>
#include <glm/geometric.hpp>
#include <glm/matrix.hpp>

#include "hdHair/base/Diagnostics.h"
#include "hdHair/gl/GpuMemory.h"
#include "hdHair/meshes/PreparedMesh.h"
#include "hdHair/render/FrameResources.h"
#include "hdHair/plan/RenderSettings.h"
#include "hdHair/render/RenderResult.h"
#include "hdHair/render/ShadowPassUniforms.h"
#include "hdHair/render/StrandShadingFeatures.h"

namespace hdhair {

namespace {

// How a pass's code uses a resource: reads it, writes it, or updates it in
// place (both).
enum class Access { Read, Write, Update };

// Checks that the running pass declared `resource` for `access`, when the
// frame checks (FrameContext::checkAccess): a pass whose code touches what
// its FramePass does not declare is a wiring mistake, never bad input, and
// the graph's culling would be wrong about it.
void touch(FrameContext& context, const FrameResource& resource, Access access) {
    if (!context.checkAccess || !context.pass) return;
    const FramePass& pass = *context.pass;
    auto declares = [&](const std::vector<FrameResource>& list) {
        return std::find(list.begin(), list.end(), resource) != list.end();
    };
    const bool reads = access != Access::Write, writes = access != Access::Read;
    if ((reads && !declares(pass.reads)) || (writes && !declares(pass.writes)))
        throw std::logic_error(fmt::format("frame graph: pass '{}' {} '{}', which it does not declare", pass.name,
                                           reads && !declares(pass.reads) ? "reads" : "writes",
                                           context.plan.graph().nameOf(resource)));
}

// The frame's images a pass draws into: colour and depth, and the ids when
// the frame has them and the pass writes them. Nothing when `target` is a
// light batch's own (the batch adds it onto the colour itself).
void touchFrameImages(FrameContext& context, const gl::RenderTarget& target, Access access, bool writesIds) {
    if (&target != context.target) return;
    touch(context, ResourceKind::Color, access);
    touch(context, ResourceKind::Depth, access);
    if (writesIds && context.inputs.idsRequested) touch(context, ResourceKind::Ids, Access::Write);
}

// The lights of one batch; the dome's ambient or uniform term belongs to
// the first batch only, so that summing batches counts it once. An SRBF
// light is kind 2 (lightVector.w), its bandwidth in lightScale.w.
gl::LightUniforms lightUniforms(const RenderPlan& plan, size_t batch) {
    const FrameRecipe& recipe = plan.recipe();
    gl::LightUniforms uniforms;
    auto [begin, end] = recipe.lighting.batches[batch];
    size_t count = end - begin;
    for (size_t i = 0; i < count; ++i) {
        const ShadingLight& light = recipe.lighting.lights.lights[begin + i];
        const float kind = light.isSrbf() ? 2.0f : light.isLocal ? 1.0f : 0.0f;
        uniforms.lightVector[i] = glm::vec4(light.directionOrPosition, kind);
        uniforms.lightScale[i] = glm::vec4(light.scale, light.srbfBandwidth);
        uniforms.lightAxis[i] = glm::vec4(light.emissionAxis, light.oneSided ? 1.0f : 0.0f);
        uniforms.lightCone[i] = glm::vec4(light.coneCosOuter, light.coneCosInner, light.shaped ? 1.0f : 0.0f, 0.0f);
    }
    uniforms.lightCount = glm::ivec4(int(count), int(batch), 0, 0);
    // w: 0 a flat ambient term (domeLighting=ambient, or no dome), 1 the
    // uniform dome's analytic response (srbf), which shades from the tables.
    const bool uniformDome = glm::length(recipe.lighting.lights.uniformDome) > 0.0f;
    const glm::vec3 dome = uniformDome ? recipe.lighting.lights.uniformDome : recipe.lighting.lights.ambient;
    uniforms.ambient = batch == 0 ? glm::vec4(dome, uniformDome ? 1.0f : 0.0f) : glm::vec4(0.0f);
    return uniforms;
}

void sortAndSend(FrameContext& context) {
    touch(context, ResourceKind::PreparedStrands, Access::Read);
    touch(context, ResourceKind::DrawOrder, Access::Write);
    const CameraView& camera = *context.inputs.camera;
    binSortSegments(context.inputs.sortSpans, camera.position(), camera.forward(),
                    context.plan.recipe().transparency.sortBins, context.drawOrder);
    // Once a frame: every light batch draws with the same order. The pass
    // makes its order buffer without naming it; it is the draw order's.
    const gl::GpuMemoryUse use("drawOrder");
    context.resources.strandPass.setDrawOrder(context.drawOrder);
}

// preparedStrands -> strands: what changed since the last frame, and the
// materials when they changed.
void upload(FrameContext& context) {
    touch(context, ResourceKind::PreparedStrands, Access::Read);
    touch(context, ResourceKind::Strands, Access::Write);
    FrameInputs& inputs = context.inputs;
    gl::StrandGeometry& strands = context.resources.strands;
    strands.reserve(inputs.uploads.capacityNeeded, inputs.uploads.controlCapacityNeeded);
    for (const StrandWrite& write : inputs.uploads.writes) {
        if (write.materialOnly) continue;  // the table below carries it
        strands.write(inputs.uploads.ranges[write.prim].first, inputs.uploads.firstControls[write.prim],
                      *inputs.drawn[write.prim].curves, inputs.uploads.slots[write.prim]);
    }
    // The drawn prims' ids and materials: a few bytes a prim, sent whole.
    std::vector<glm::ivec4> slots(std::max<size_t>(inputs.uploads.slotCount, 1), glm::ivec4(0));
    for (size_t i = 0; i < inputs.drawn.size(); ++i)
        slots[inputs.uploads.slots[i]] =
            glm::ivec4(inputs.drawn[i].primAndInstance, inputs.drawn[i].material, 0);
    strands.writeDrawnPrims(slots);
    if (inputs.materials)
        context.resources.materials.update(inputs.materials->materials, inputs.materials->parameterPoints,
                                           inputs.materials->tables, inputs.materials->tableWidth,
                                           inputs.materials->tableHeight);
    if (inputs.materials) {
        const SrbfTableUpload& srbf = inputs.materials->srbfTables;
        const gl::GpuMemoryUse use("srbfTables");
        context.resources.srbfTables.update(srbf.marschner, srbf.kajiyaKay, srbf.uniformRows);
    }
}

// preparedMeshes -> meshGeometry: every drawn mesh, when one changed.
void meshUpload(FrameContext& context) {
    touch(context, ResourceKind::PreparedMeshes, Access::Read);
    touch(context, ResourceKind::MeshGeometry, Access::Write);
    const MeshUpload& meshes = context.inputs.meshes;
    if (!meshes.changed) return;
    gl::MeshGeometry& geometry = context.resources.meshes;
    geometry.reserve(meshes.vertices);
    for (size_t i = 0; i < meshes.meshes.size(); ++i) geometry.write(meshes.draws[i].first, meshes.meshes[i]->vertices);
}

// The parts of the strand shading a draw of light batch `batch` can reach
// (StrandShadingFeatures.h), or the ids pass's (`ids`: none); all of them
// with specializeShaders off. Either way a colour draw's deep opacity
// lookups are taken per point when the plan says so (shadowSampling). Each
// set the frame uses is named once in the stats.
gl::ShadingFeatures strandFeatures(FrameContext& context, size_t batch, bool ids) {
    const FrameRecipe& recipe = context.plan.recipe();
    gl::ShadingFeatures features = !recipe.execution.specializeShaders ? gl::ShadingFeatures::all()
                                   : ids                               ? gl::ShadingFeatures()
                                         : batchShadingFeatures(recipe, batch, context.inputs.materialFeatures);
    if (recipe.shadows.perVertex && !ids) features.setVertexShadowLights(batchVertexShadowLights(recipe, batch));
    std::vector<std::string>& named = context.result.stats.strandShaders;
    const std::string name = features.describe();
    if (std::find(named.begin(), named.end(), name) == named.end()) named.push_back(name);
    return features;
}

// Binds `target` and what a pass drawing light batch `batch` reads besides
// its geometry: the hair materials, the frame's and the batch's lights'
// uniforms, and their shadow maps (meshes and strands alike). Returns the
// shading features the strand programs compile for it.
gl::ShadingFeatures bindBatchInputs(FrameContext& context, gl::RenderTarget& target, size_t batch) {
    FrameResources& resources = context.resources;
    target.bind();
    resources.materials.bind();
    resources.srbfTables.bind();
    resources.shadowMaps.bindForLookup();
    resources.shadowReference.bindForLookup();
    resources.densityVolume.bind();
    const gl::LightUniforms lights = lightUniforms(context.plan, batch);
    const gl::ShadowUniforms shadows = batchShadowUniforms(context.plan.recipe(), batch);
    const gl::ShadingFeatures features = strandFeatures(context, batch, false);
    resources.strandPass.setUniforms(context.inputs.frame, lights, shadows, features);
    return features;
}

// The maps the programs of light batch `batch` look up, as their uniforms
// name them by slot: each planned shadow's map and the meshes' depth, and,
// for the strands, the mip chain when an SRBF light reads through it.
void touchBatchShadows(FrameContext& context, size_t batch, bool strands) {
    const FrameRecipe& recipe = context.plan.recipe();
    const ShadowPlan& shadows = recipe.shadows;
    const gl::ShadowUniforms uniforms = batchShadowUniforms(context.plan.recipe(), batch);
    const auto [begin, end] = recipe.lighting.batches[batch];
    for (size_t entry = 0; entry < end - begin && entry < size_t(gl::kMaxLightsPerPass); ++entry) {
        const int slot = int(uniforms.lightMap[entry].x), meshSlot = int(uniforms.meshMap[entry].x);
        for (size_t shadow = 0; shadow < shadows.lights.size(); ++shadow) {
            const PlannedShadow& planned = shadows.lights[shadow];
            if (slot >= 0 && shadows.isMapped(planned) && planned.slot == slot)
                touch(context, shadows.resourceOf(shadow), Access::Read);
            if (meshSlot >= 0 && shadows.isMeshMapped(planned) && planned.slot == meshSlot)
                touch(context, shadows.meshResourceOf(shadow), Access::Read);
        }
        if ((uniforms.volume.x >> entry) & 1) touch(context, ResourceKind::DensityVolume, Access::Read);
        if (strands && shadows.convolvedOpacity && recipe.lighting.lights.lights[begin + entry].isSrbf())
            touch(context, ResourceKind::ConvolvedOpacity, Access::Read);
    }
    if (strands && shadows.volumeBackScattering && shadows.usesVolume())
        touch(context, ResourceKind::DensityVolume, Access::Read);
    if (strands && batch == 0 && shadows.volumeDomeOcclusion && shadows.usesVolume())
        touch(context, ResourceKind::DensityVolume, Access::Read);
}

// Draws the meshes lit by the lights of one batch into `target`, before the
// strands: their depth is what every strand path tests against.
void drawMeshes(FrameContext& context, gl::RenderTarget& target, size_t batch) {
    touch(context, ResourceKind::MeshGeometry, Access::Read);
    touchFrameImages(context, target, Access::Update, true);
    if (context.plan.recipe().lighting.meshesLit) touchBatchShadows(context, batch, false);
    bindBatchInputs(context, target, batch);
    context.resources.meshPass.draw(
        context.resources.meshes, context.inputs.meshes.draws, context.inputs.frame.viewProjection,
        context.plan.recipe().lighting.meshesLit ? gl::MeshShading::Lit : gl::MeshShading::Unlit);
}

void clear(FrameContext& context) {
    const CameraView& camera = *context.inputs.camera;
    // Blended frames take their depth from the strand pass's min-blended
    // nearest depth (or the exact resolve), not from the depth buffer.
    const gl::RenderTargetImages images{context.inputs.idsRequested,
                                        context.plan.recipe().transparency.path != TransparencyPath::Opaque,
                                        context.inputs.samples};
    context.target = &context.resources.frameTarget(camera.imageWidth, camera.imageHeight, images);
    touch(context, ResourceKind::Color, Access::Write);
    touch(context, ResourceKind::Depth, Access::Write);
    if (context.inputs.idsRequested) touch(context, ResourceKind::Ids, Access::Write);
    // Empty pixels are transparent black: pre-multiplied "nothing".
    context.target->bindAndClear(glm::vec4(0.0f));
}

// Draws the strands with the uniforms bound (ordered: in the draw order the
// sort sent; else the drawn prims' ranges). A frame that can be cancelled
// draws them in pieces of strandPieceSegments and finishes each piece's GL
// work before asking whether to stop: llvmpipe rasterises only when work is
// flushed, so without the finish a camera move would wait for the whole
// pass. The pieces are consecutive runs of the order (or of the ranges), and
// blending and the depth test see primitives in the same order across draws
// as within one, so the pieces give the single draw's image to the bit
// (testFrameCancellation: every transparency path, pieces of 7 segments).
void drawStrandPieces(FrameContext& context, bool ordered, gl::StrandBlending blending) {
    FrameResources& resources = context.resources;
    const std::vector<gl::SegmentRange>& ranges = context.inputs.uploads.drawRanges;
    const size_t piece = context.strandPieceSegments;
    if (!context.cancellation || piece == 0) {
        resources.strandPass.draw(resources.strands, ranges, blending);
        return;
    }
    if (ordered) {
        const std::vector<uint32_t>& order = context.drawOrder;
        for (size_t first = 0; first < order.size() && !stopRequested(context); first += piece) {
            const size_t end = std::min(order.size(), first + piece);
            resources.strandPass.setDrawOrder(std::vector<uint32_t>(order.begin() + ptrdiff_t(first),
                                                                    order.begin() + ptrdiff_t(end)));
            resources.strandPass.draw(resources.strands, {}, blending);
            glFinish();
        }
        return;
    }
    for (const std::vector<gl::SegmentRange>& pieceRanges : gl::piecesOf(ranges, piece)) {
        if (stopRequested(context)) return;
        resources.strandPass.draw(resources.strands, pieceRanges, blending);
        glFinish();
    }
}

// MB for `fragments` list nodes, rounded up.
uint64_t fragmentListMB(uint64_t fragments) { return (fragments * gl::kFragmentNodeBytes + (1 << 20) - 1) >> 20; }

// Reports the lists just resolved: their fragments and tiles, and a warning
// when some pixel's list was too long to sort whole, or to walk whole; once a
// frame: every light batch lists the same fragments.
void reportLists(FrameContext& context, uint64_t fragments, size_t batch) {
    const gl::FragmentListPass& lists = context.resources.fragmentLists;
    RenderStats& stats = context.result.stats;
    stats.fragments = fragments;
    stats.resolvedListTiles = lists.resolvedTiles();
    stats.listTiles = lists.tilesInImage();
    if (batch != 0) return;
    if (lists.overlongPixels() > 0)
        context.diagnostics.warn("render", fmt::format("{} pixel(s) held more than 180 strand fragments: each was "
                                                       "composited in depth order for its nearest 64 and as one "
                                                       "alpha-weighted layer behind them",
                                                       lists.overlongPixels()));
    if (lists.unwalkedPixels() > 0)
        context.diagnostics.warn("render", fmt::format("{} pixel(s) held more strand fragments than the GL driver "
                                                       "lets one shader walk (llvmpipe: 65535 loop steps); their "
                                                       "last-listed fragments are missing from the picture",
                                                       lists.unwalkedPixels()));
}

// Who lists each drawn prim's segments: the compute rasteriser, but for the
// prims the plan gives the hardware rasteriser (into the same lists).
gl::ListedSegments listedSegments(const RenderPlan& plan, const StrandUploadPlan& uploads) {
    const FrameRecipe& recipe = plan.recipe();
    if (!recipe.strandRaster.mixesRasterisers()) return {{}, uploads.drawRanges};
    gl::ListedSegments segments;
    for (size_t prim = 0; prim < uploads.ranges.size(); ++prim)
        (recipe.strandRaster.listedByHardware.at(prim) ? segments.hardware : segments.compute)
            .push_back(uploads.ranges[prim]);
    return {gl::joinedRanges(segments.hardware), gl::joinedRanges(segments.compute)};
}

// Stops the frame for a new plan: what this one asked of a pass cannot be done.
void fallBack(FrameContext& context, FrameFallback::Kind kind, const std::string& reason,
              const std::string& shadowKey = "") {
    context.fallback = FrameFallback{kind, reason, shadowKey};
    context.stopped = true;
}

// Lists the blended strands into per-pixel lists and resolves them
// (compute rasteriser or exact transparency), within `capacity`
// fragments. Over it, the frame stops for a new plan without them, or fails
// (exactOverflow=fail: a reference that quietly became an approximation
// would be measured against as if it were exact).
void listStrands(FrameContext& context, gl::RenderTarget& target, size_t batch, const gl::ShadingFeatures& features,
                 bool compute) {
    FrameInputs& inputs = context.inputs;
    const RenderPlan& plan = context.plan;
    FrameResources& resources = context.resources;
    const CameraView& camera = *inputs.camera;
    // A frame that can be cancelled lists its fragments in pieces, as
    // drawStrandPieces draws.
    gl::ListFilling filling;
    if (context.cancellation) {
        filling.pieceSegments = context.strandPieceSegments;
        filling.stopRequested = [&context] { return stopRequested(context); };
    }
    touchFrameImages(context, target, Access::Update, true);  // the resolve writes depth and ids
    const size_t capacity = compute ? inputs.computeRasterCapacity : inputs.fragmentListCapacity;
    const uint64_t fragments = resources.fragmentLists.render(
        resources.strands,
        compute ? listedSegments(plan, inputs.uploads) : gl::ListedSegments{inputs.uploads.drawRanges, {}},
        camera.imageWidth, camera.imageHeight, capacity, plan.recipe().strandRaster.expectedFragments,
        inputs.frame.maxSegmentsPerSpan, target.images().ids, features, compute ? target.depthTexture() : 0, filling);
    if (resources.fragmentLists.stopped()) return;
    if (fragments <= capacity) return reportLists(context, fragments, batch);
    context.result.stats.fragments = fragments;
    if (compute) {
        context.diagnostics.warn(
            "render", fmt::format("the compute rasteriser needs {} MB for {} fragments, more than "
                                  "strandRasterMemoryMB={}; drawn by the hardware rasteriser instead",
                                  fragmentListMB(fragments), fragments, plan.recipe().strandRaster.memoryMB));
        return fallBack(context, FrameFallback::Kind::ComputeListsOverBudget,
                        "compute -> hardware rasteriser: fragment lists over strandRasterMemoryMB");
    }
    const std::string needed = fmt::format(
        "exact transparency needs {} MB for {} fragments, more than "
        "exactMemoryMB={}",
        fragmentListMB(fragments), fragments, plan.recipe().transparency.exactMemoryMB);
    if (plan.recipe().transparency.exactOverflowFails) {
        context.failure = needed + " (exactOverflow=fail: raise exactMemoryMB or lower supersampling)";
        context.stopped = true;
        return;
    }
    context.diagnostics.warn("render", fmt::format("{}; rendered with binSorted ({} bins) instead", needed,
                                                   kFallbackSortBins));
    fallBack(context, FrameFallback::Kind::ExactListsOverBudget,
             fmt::format("exact -> binSorted ({} bins): fragment lists over exactMemoryMB", kFallbackSortBins));
}

// Draws the strands with the lights of one batch into `target`, over what
// it holds (the meshes of that batch, or nothing), as the plan says: listed
// and resolved (compute rasteriser, exact transparency), or drawn blended
// or opaque by the hardware.
void drawStrands(FrameContext& context, gl::RenderTarget& target, size_t batch) {
    const FrameRecipe& recipe = context.plan.recipe();
    touch(context, ResourceKind::Strands, Access::Read);
    touchBatchShadows(context, batch, true);
    const gl::ShadingFeatures features = bindBatchInputs(context, target, batch);
    if (recipe.strandRaster.rasteriser == StrandRaster::Compute)
        return listStrands(context, target, batch, features, true);
    if (recipe.transparency.path == TransparencyPath::Exact)
        return listStrands(context, target, batch, features, false);
    const bool ordered = context.inputs.frame.orderedDraw != 0;
    if (ordered) touch(context, ResourceKind::DrawOrder, Access::Read);
    // Blended, the ids are the ids pass's; opaque, the depth test keeps them here.
    const bool opaque = recipe.transparency.path == TransparencyPath::Opaque;
    touchFrameImages(context, target, Access::Update, opaque);
    drawStrandPieces(context, ordered, opaque ? gl::StrandBlending::Opaque : gl::StrandBlending::PremultipliedOver);
}

void ids(FrameContext& context) {
    touch(context, ResourceKind::Strands, Access::Read);
    touch(context, ResourceKind::Depth, Access::Read);
    touch(context, ResourceKind::Ids, Access::Write);
    gl::FrameUniforms idsFrame = context.inputs.frame;
    idsFrame.drawMode = 2;
    idsFrame.orderedDraw = 0;
    const gl::LightUniforms lights = lightUniforms(context.plan, 0);
    const gl::ShadowUniforms noShadows{};
    context.resources.strandPass.setUniforms(idsFrame, lights, noShadows, strandFeatures(context, 0, true));
    drawStrandPieces(context, false, gl::StrandBlending::IdsOnly);
}

// "lightBatch k": the meshes and strands again with lights of batch k - 1
// (0-based), added onto the frame's resolved colour.
void lightBatch(FrameContext& context, size_t batch) {
    const CameraView& camera = *context.inputs.camera;
    gl::RenderTarget& batchTarget =
        context.resources.lightBatchTarget(camera.imageWidth, camera.imageHeight, context.inputs.samples);
    batchTarget.bindAndClear(glm::vec4(0.0f));
    if (context.plan.isEnabled(PassKind::Meshes)) drawMeshes(context, batchTarget, batch);
    if (context.plan.isEnabled(PassKind::Strands)) drawStrands(context, batchTarget, batch);
    batchTarget.resolve();
    touch(context, ResourceKind::Color, Access::Update);
    context.resources.lightBatchAccumulation.add(*context.target, batchTarget);
}

void prepareShadowMaps(FrameContext& context) {
    const ShadowPlan& shadows = context.plan.recipe().shadows;
    context.resources.shadowMaps.ensure(shadows.resolution, (shadows.layers + 3) / 4, std::max(shadows.capacity, 1),
                                        shadows.convolvedOpacity);
}

// How light L's view draws the strands, as planned.
gl::LightViewStrands lightViewStrands(const PlannedShadow& shadow) {
    if (!shadow.strandLines) return gl::LightViewStrands::Ribbons;
    if (shadow.computeLines) return gl::LightViewStrands::ComputeLines;
    return shadow.straightSpans ? gl::LightViewStrands::Lines : gl::LightViewStrands::TessellatedLines;
}

// The hair in light L's view, as shadowDepth or deepOpacity draws it.
void hairShadowMap(FrameContext& context, size_t shadow, PassKind kind) {
    touch(context, ResourceKind::Strands, Access::Read);
    if (kind == PassKind::DeepOpacity) {
        touch(context, {ResourceKind::HairDepth, shadow}, Access::Read);
        touch(context, {ResourceKind::DeepOpacity, shadow}, Access::Write);
    } else {
        touch(context, {ResourceKind::HairDepth, shadow}, Access::Write);
    }
    prepareShadowMaps(context);
    FrameResources& resources = context.resources;
    const gl::FrameUniforms view = lightViewFrameUniforms(context.plan.recipe(), shadow, context.inputs.frame);
    const gl::ShadowUniforms uniforms = lightShadowUniforms(context.plan.recipe(), shadow);
    const gl::LightViewStrands drawn = lightViewStrands(context.plan.recipe().shadows.lights[shadow]);
    if (kind == PassKind::ShadowDepth)
        resources.shadowMapPass.renderDepth(resources.shadowMaps, resources.strands, context.inputs.uploads.drawRanges,
                                            view, uniforms, drawn);
    else
        resources.shadowMapPass.renderOpacity(resources.shadowMaps, resources.strands,
                                              context.inputs.uploads.drawRanges, view, uniforms, drawn);
}

// "shadowDepth L": the nearest hair in light L's view.
void shadowDepth(FrameContext& context, size_t shadow) { hairShadowMap(context, shadow, PassKind::ShadowDepth); }

// "deepOpacity L": light L's opacity layers behind that hair.
void deepOpacity(FrameContext& context, size_t shadow) { hairShadowMap(context, shadow, PassKind::DeepOpacity); }

// "meshShadow L": the nearest mesh in light L's mesh view.
void meshShadow(FrameContext& context, size_t shadow) {
    touch(context, ResourceKind::MeshGeometry, Access::Read);
    touch(context, {ResourceKind::MeshDepth, shadow}, Access::Write);
    prepareShadowMaps(context);
    FrameResources& resources = context.resources;
    resources.shadowMapPass.renderMeshDepth(resources.shadowMaps, resources.meshPass, resources.meshes,
                                            context.inputs.meshes.draws,
                                            meshViewFrameUniforms(context.plan.recipe(), shadow, context.inputs.frame),
                                            lightShadowUniforms(context.plan.recipe(), shadow));
}

// "densityVolume": every drawn prim's strands into the density grid the
// plan sized, sent to the GPU.
void densityVolume(FrameContext& context) {
    touch(context, ResourceKind::PreparedStrands, Access::Read);
    touch(context, ResourceKind::DensityVolume, Access::Write);
    DensityGrid grid(context.plan.recipe().shadows.volumeGrid);
    for (const DrawnPrim& drawn : context.inputs.drawn) addStrandsToGrid(grid, *drawn.curves);
    const gl::GpuMemoryUse use("densityVolume");
    context.resources.densityVolume.update(grid);
}

// "opacityMipmaps": the mip chain of every map (ShadowMapStorage says why
// all at once).
void opacityMipmaps(FrameContext& context) {
    const ShadowPlan& shadows = context.plan.recipe().shadows;
    for (size_t shadow = 0; shadow < shadows.lights.size(); ++shadow)
        if (shadows.isMapped(shadows.lights[shadow])) touch(context, shadows.resourceOf(shadow), Access::Read);
    touch(context, ResourceKind::ConvolvedOpacity, Access::Write);
    prepareShadowMaps(context);
    context.resources.shadowMaps.generateOpacityMipmaps();
}

// "shadowFragments L": every fragment of light L's view (shadowMode=reference).
void shadowFragments(FrameContext& context, size_t shadow) {
    const FrameRecipe& recipe = context.plan.recipe();
    touch(context, ResourceKind::Strands, Access::Read);
    touch(context, {ResourceKind::ShadowFragments, shadow}, Access::Write);
    FrameResources& resources = context.resources;
    const PlannedShadow& planned = recipe.shadows.lights[shadow];
    resources.shadowReference.ensure(recipe.shadows.resolution, std::max(recipe.shadows.capacity, 1));
    if (!context.shadowPoolEmptied) resources.shadowReference.reset();
    context.shadowPoolEmptied = true;
    bool written = false;
    const uint64_t nodes =
        resources.shadowReference.render(resources.strands, context.inputs.uploads.drawRanges,
                                         lightViewFrameUniforms(context.plan.recipe(), shadow, context.inputs.frame),
                                         lightShadowUniforms(context.plan.recipe(), shadow), &written);
    if (written) return;
    const std::string needed = fmt::format("shadowMode=reference needs {} MB of light-view fragments, more than one "
                                           "GL storage block holds",
                                           (nodes * gl::kShadowNodeBytes + (1 << 20) - 1) >> 20);
    context.diagnostics.warn(planned.key,
                             needed + "; this light is shaded without its shadows (lower shadowMapResolution)");
    context.unbuiltShadowMaps.push_back(planned.key);
    fallBack(context, FrameFallback::Kind::ShadowMapUnbuildable, planned.key + ": " + needed, planned.key);
}

// An image of `channels` holding `pixels` as read back: made around them, so
// that a frame's floats are never held twice (Image(w, h, c) would allocate
// and zero a frame of its own first).
Image imageOf(int width, int height, int channels, std::vector<float> pixels) {
    Image image;
    image.width = width;
    image.height = height;
    image.channels = channels;
    image.pixels = std::move(pixels);
    return image;
}

void readback(FrameContext& context) {
    touch(context, ResourceKind::Color, Access::Read);
    if (context.inputs.depthRequested) touch(context, ResourceKind::Depth, Access::Read);
    if (context.inputs.idsRequested) touch(context, ResourceKind::Ids, Access::Read);
    touch(context, ResourceKind::Aovs, Access::Write);
    const CameraView& camera = *context.inputs.camera;
    RenderResult& result = context.result;
    result.color = imageOf(camera.imageWidth, camera.imageHeight, 4, context.target->readColor());
    if (context.inputs.depthRequested)
        result.depth = imageOf(camera.imageWidth, camera.imageHeight, 1, context.target->readDepth());
    if (context.inputs.idsRequested) {
        result.primIds = context.target->readIds(0);
        result.instanceIds = context.target->readIds(1);
        result.elementIds = context.target->readIds(2);
    }
}

// The display image from the frame's resolved colour, on the GPU.
void displayTransform(FrameContext& context) {
    touch(context, ResourceKind::Color, Access::Read);
    touch(context, ResourceKind::DisplayImage, Access::Write);
    const CameraView& camera = *context.inputs.camera;
    context.result.display = imageOf(
        camera.imageWidth, camera.imageHeight, 4,
        context.resources.displayTransform.run(*context.inputs.gpuDisplay, context.target->resolvedColorTexture(),
                                               camera.imageWidth, camera.imageHeight, context.inputs.displayOverBlack));
}

// "resolve": the multisampled images averaged, in place.
void resolve(FrameContext& context) {
    touchFrameImages(context, *context.target, Access::Update, true);
    context.target->resolve();
}

}  // namespace

bool isCpuPass(const FramePass& pass) { return pass.kind == PassKind::Sort; }

bool stopRequested(FrameContext& context) {
    if (!context.stopped && context.cancellation && context.cancellation->requested()) context.stopped = true;
    return context.stopped;
}

bool runsWhenStopped(const FramePass& pass) {
    return pass.kind == PassKind::Upload || pass.kind == PassKind::MeshUpload;
}

std::optional<size_t> shadowMapBuiltBy(const FramePass& pass) {
    switch (pass.kind) {
    case PassKind::ShadowDepth:
    case PassKind::DeepOpacity:
    case PassKind::MeshShadow:
    case PassKind::ShadowFragments: return pass.subject;
    default: return std::nullopt;
    }
}

void runFramePass(const FramePass& pass, FrameContext& context) {
    switch (pass.kind) {
    case PassKind::Upload: return upload(context);
    case PassKind::MeshUpload: return meshUpload(context);
    case PassKind::Sort: return sortAndSend(context);
    case PassKind::ShadowDepth: return shadowDepth(context, pass.subject);
    case PassKind::DeepOpacity: return deepOpacity(context, pass.subject);
    case PassKind::ShadowFragments: return shadowFragments(context, pass.subject);
    case PassKind::MeshShadow: return meshShadow(context, pass.subject);
    case PassKind::OpacityMipmaps: return opacityMipmaps(context);
    case PassKind::DensityVolume: return densityVolume(context);
    case PassKind::Clear: return clear(context);
    case PassKind::Meshes: return drawMeshes(context, *context.target, 0);
    case PassKind::Strands: return drawStrands(context, *context.target, 0);
    case PassKind::Ids: return ids(context);
    case PassKind::Resolve: return resolve(context);
    case PassKind::LightBatch: return lightBatch(context, pass.subject);
    case PassKind::Readback: return readback(context);
    case PassKind::DisplayTransform: return displayTransform(context);
    }
    throw std::logic_error("frame graph: pass '" + pass.name + "' has no kind the renderer runs");
}

}  // namespace hdhair
