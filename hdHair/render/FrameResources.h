#pragma once
// The GL objects a frame's passes use (FramePasses.h), made once and kept
// between frames: the compiled passes, the strand and mesh geometry and the
// hair materials on the GPU, the lights' shadow maps, and the frame's render
// targets, remade only when the image size or the images a frame needs
// change. Created, used and destroyed on the GL thread only.

#include <memory>

#include "hdHair/gl/DensityVolumeTexture.h"
#include "hdHair/gl/DisplayTransformPass.h"
#include "hdHair/gl/FragmentListPass.h"
#include "hdHair/gl/HairMaterialTable.h"
#include "hdHair/gl/SrbfTableTextures.h"
#include "hdHair/gl/LightBatchAccumulation.h"
#include "hdHair/gl/MeshGeometry.h"
#include "hdHair/gl/MeshPass.h"
#include "hdHair/gl/RenderTarget.h"
#include "hdHair/gl/ShadowMapPass.h"
#include "hdHair/gl/ShadowMapStorage.h"
#include "hdHair/gl/ShadowReferencePass.h"
#include "hdHair/gl/StrandGeometry.h"
#include "hdHair/gl/StrandPass.h"

namespace hdhair {

struct FrameResources {
    FrameResources();  // compiles the programs; throws on driver errors

    // The frame's target (colour, depth, and the images `images` asks for),
    // and the one later light batches draw into before they are added.
    gl::RenderTarget& frameTarget(int width, int height, const gl::RenderTargetImages& images);
    gl::RenderTarget& lightBatchTarget(int width, int height, int samples);

    gl::StrandPass strandPass;
    gl::MeshPass meshPass;
    gl::FragmentListPass fragmentLists;
    gl::LightBatchAccumulation lightBatchAccumulation;
    gl::HairMaterialTable materials;
    gl::SrbfTableTextures srbfTables;  // dome lighting
    gl::StrandGeometry strands;
    gl::DisplayTransformPass displayTransform;
    gl::MeshGeometry meshes;
    // Every light's shadow, kept between frames (hdHair/render/ShadowMapCache.h
    // says which to rebuild).
    gl::ShadowMapStorage shadowMaps;
    gl::ShadowMapPass shadowMapPass;
    gl::ShadowReferencePass shadowReference;
    gl::DensityVolumeTexture densityVolume;  // the hair's density, for lights shadowed through it
    int maxSamples = 0;  // the driver's GL_MAX_SAMPLES

private:
    std::unique_ptr<gl::RenderTarget> target_, batchTarget_;
};

}  // namespace hdhair
