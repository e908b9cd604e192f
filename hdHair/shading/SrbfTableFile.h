#pragma once
// The on-disk form of one SRBF-convolution table (SrbfConvolutionTables.h),
// for SrbfTableCache.h. Native byte order (little-endian on every platform
// hdHair builds for; a byte-swapped file fails the magic check):
//   8 bytes   magic "hdHSRBF\0"
//   u32       kSrbfTableFileVersion
//   u32       key length K, then K bytes: the request's key (srbfTableKey)
//   u32 kind, i32 azimuths, outgoing, centres, bandwidths, u32 precision, u32 channels
//   u64       texel count N (= W·H·D·channels)
//   u64       FNV-1a 64 checksum of the N floats' bytes
//   N × f32   the texels, in the table's layout
// A file is used only if every field checks out, the key equals the one
// asked for (so a hash collision in the file name cannot serve the wrong
// table) and the file ends exactly after the texels.

#include <cstdint>
#include <string>

#include "hdHair/shading/SrbfConvolutionTables.h"

namespace hdhair {

constexpr std::uint32_t kSrbfTableFileVersion = 1;

// FNV-1a, 64 bits (Fowler, Noll & Vo): the file's checksum and name hash.
std::uint64_t fnv1a64(const void* data, std::size_t size, std::uint64_t seed = 0xcbf29ce484222325ull);

// Writes atomically (AtomicFile.h); throws std::runtime_error on failure.
void writeSrbfTableFile(const std::string& path, const std::string& key, const SrbfConvolutionTable& table);

// Reads `path` into `table` if it is a valid file for `key`. Returns "" on
// success, else why not in a few words ("checksum mismatch", "truncated").
std::string readSrbfTableFile(const std::string& path, const std::string& key, SrbfConvolutionTable& table);

}  // namespace hdhair
