#pragma once
// Reads Cem Yuksel's .hair format (cemyuksel.com/research/hairmodels) into
// HairStrands (TressFxReader.h).
//
// Format (little-endian): a 128-byte header: char[4] "HAIR", uint32 hair
// count, uint32 point count, uint32 array bit field (bit 0 segments, bit 1
// points, bit 2 thickness, bit 3 transparency, bit 4 colors), uint32 default
// segments, float default thickness, float default transparency, float3
// default color, char[88] info. Then the arrays the bit field names, in that
// order: segments (uint16 per hair; a hair has segments + 1 points), points
// (float3 per point), thickness (float per point), transparency (float per
// point), color (float3 per point).
//
// Mapping: thickness -> HairStrands::widths (a curve width, in scene units),
// colour -> colors, 1 - transparency -> opacities. When an array is absent the
// header's default applies to every vertex and is kept as defaultWidth /
// defaultColor / defaultOpacity, except values that mean "not given": a
// default thickness <= 0, a default transparency <= 0 (opaque is the
// fallback anyway) and a black default colour (a zeroed header).
//
// Validation: the magic, a points array (bit 1), the point count against the
// sum of the segment counts, every array against the file size, hairs with
// at least 1 segment, finite values. Errors throw std::runtime_error with one
// line starting with the file's name.

#include <cstdint>
#include <string>
#include <vector>

#include "hdHair/assets/TressFxReader.h"

namespace hdhair::convert {

HairStrands readYukselHair(const std::string& path);
HairStrands parseYukselHair(const std::vector<std::uint8_t>& bytes, const std::string& name);

}  // namespace hdhair::convert
