#pragma once
// Where every light's deep opacity map lives: one slot per shadow-casting
// light (hdHair/render/ShadowMapCache.h assigns them), in three 2D array
// textures, so that the lookup needs three texture units however many lights
// a pass shades (16 at most, kMaxLightsPerPass): the nearest hair's linear
// depth (R32F, one layer a slot), the opacity layers (RGBA16F, 16-bit floats
// as in the thesis, section 2.7.2: 4 layers a texel, ceil(layers / 4) array
// layers a slot) and the nearest mesh's linear depth (R32F, one layer a slot). Maps are kept between frames; changing the resolution, the
// layer count or the number of slots reallocates, which loses them (the
// cache rebuilds them all then).
//
// Half floats add alpha exactly to 2048 x 2^-11 steps; past that, sums of
// faint fragments round away (at an opacity of 8 a step below 2^-8 is lost),
// but by then exp(-8) = 0.0003 of the light is left: the loss cannot show.

#include "hdHair/gl/GlObjects.h"

namespace hdhair::gl {

class ShadowMapStorage {
public:
    ShadowMapStorage();  // one 1x1 slot, so the lookup always has textures to bind

    // Makes room for `slots` maps of resolution^2 texels and `layerTargets`
    // RGBA16F layers each; reallocates (contents lost) only when they change.
    // `opacityMipmaps`: the opacity layers get a mip chain, the convolution
    // optical depth map SRBF lights read (generateOpacityMipmaps; 1/3 more
    // opacity memory), only while a frame asks for it.
    void ensure(int resolution, int layerTargets, int slots, bool opacityMipmaps = false);

    // Averages every slot's opacity layers down the mip chain (level k: the
    // mean over 2^k × 2^k texels), after the maps were drawn. The whole
    // array at once: on llvmpipe, a texture view of one slot's layers cost
    // more per map than the whole array of a frame's maps (hdhair-bench
    // --table dome on Sintel: 113x the ambient frame against 20x for four
    // maps), and the cache holds about as many slots as a frame draws maps.
    void generateOpacityMipmaps();

    // Binds the framebuffer that draws slot `slot`'s nearest depth, cleared
    // to "no hair" (HDHAIR_NO_HAIR in shaders/include/shadows.glsl), with the
    // viewport set.
    void bindDepthTarget(int slot);
    // The same for slot `slot`'s nearest mesh depth.
    void bindMeshDepthTarget(int slot);
    // Binds slot `slot`'s opacity layers as draw buffers 0..targets-1,
    // cleared to 0, with the viewport set.
    void bindOpacityTargets(int slot);
    // The depth array at texture unit 2, the opacity array at unit 3 and the
    // mesh depth array at unit 4 (shadowDepths, shadowOpacity and
    // shadowMeshDepths in shaders/include/shadows.glsl).
    void bindForLookup() const;

    int resolution() const { return resolution_; }
    // For the compute rasteriser (LightViewRaster): clears slot `slot`'s
    // nearest hair depth to "no hair"; the arrays themselves.
    void clearHairDepth(int slot);
    GLuint hairDepths() const { return depths_.get(); }
    GLuint opacityLayers() const { return opacity_.get(); }

private:
    void allocate();
    // Binds layer `slot` of `depths` as the only draw buffer, cleared to
    // "nothing here".
    void bindNearestDepthTarget(const Texture& depths, int slot);

    Texture depths_, opacity_, meshDepths_;
    Framebuffer framebuffer_;
    int resolution_ = 0, targets_ = 0, slots_ = 0;
    bool opacityMipmaps_ = false;
};

}  // namespace hdhair::gl
