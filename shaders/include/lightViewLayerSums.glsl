// The per-layer sums of a light view's opacity in compute (LightViewRaster.h):
// lightViewOpacity.comp adds each texel's alpha into the one layer it starts
// counting in, lightViewLayers.comp reads them out front to back. Fixed
// point, not floats: integer sums do not depend on the order the spans
// arrive in, so a map rebuilt is the same to the bit (float atomics made
// frames differ in their last bits from one build to the next). Steps of
// 2^-16 (finer than the half-float layers' 2^-11 relative step from alpha
// 1/32 up); a sum stops growing at 2^31, an opacity of 32768, where
// exp(-k opacity) is 0 whatever follows.

// Layer k's sum for texel (x, y) at [(k * resolution + y) * resolution + x].
layout(std430, binding = 11) coherent buffer LayerSums {
    uint layerSums[];
};

const float kLayerSumSteps = 65536.0;  // steps a unit of alpha
const uint kLayerSumFull = 0x80000000u;

uint layerSumIndex(int layer, ivec2 texel, int resolution) {
    return (uint(layer) * uint(resolution) + uint(texel.y)) * uint(resolution) + uint(texel.x);
}

// Adds `alpha` to the sum at `index`. A line carries at most about 2
// (strandLinePoint.glsl); 4 bounds it, so that no add carries a sum from
// under kLayerSumFull past 2^32.
void addToLayerSum(uint index, float alpha) {
    uint steps = uint(round(min(alpha, 4.0) * kLayerSumSteps));
    if (layerSums[index] < kLayerSumFull) atomicAdd(layerSums[index], steps);
}

float layerSumOpacity(uint index) { return float(min(layerSums[index], kLayerSumFull)) / kLayerSumSteps; }
