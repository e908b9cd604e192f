#include "hdHair/render/CountingSort.h"

#include <algorithm>

#include <tbb/info.h>
#include <tbb/parallel_for.h>

namespace hdhair {

namespace {

// Enough elements a block that counting dominates the per-block prefix work
// over the keys, and a few blocks a core for balance.
size_t chooseBlocks(size_t elements, uint32_t keyCount) {
    const size_t cores = size_t(std::max(1, tbb::info::default_concurrency()));
    const size_t worthIt = std::max<size_t>(elements / std::max<size_t>(4 * size_t(keyCount), 16384), 1);
    return std::min(4 * cores, worthIt);
}

}  // namespace

template <typename Key>
void stableCountingSort(const std::vector<uint32_t>& in, const std::vector<Key>& key, uint32_t keyCount,
                        std::vector<uint32_t>& out, size_t blocks) {
    const size_t n = in.size();
    out.resize(n);
    if (blocks == 0) blocks = chooseBlocks(n, keyCount);
    blocks = std::max<size_t>(1, std::min(blocks, std::max<size_t>(n, 1)));
    auto blockBegin = [&](size_t block) { return n * block / blocks; };
    // counts[k * blocks + b]: elements of key k in block b; then, after the
    // prefix sum, where block b writes its first element of key k.
    std::vector<size_t> counts(size_t(keyCount) * blocks, 0);
    tbb::parallel_for(size_t(0), blocks, [&](size_t block) {
        for (size_t i = blockBegin(block); i < blockBegin(block + 1); ++i) ++counts[size_t(key[in[i]]) * blocks + block];
    });
    size_t running = 0;
    for (size_t& count : counts) {
        const size_t here = count;
        count = running;
        running += here;
    }
    tbb::parallel_for(size_t(0), blocks, [&](size_t block) {
        for (size_t i = blockBegin(block); i < blockBegin(block + 1); ++i)
            out[counts[size_t(key[in[i]]) * blocks + block]++] = in[i];
    });
}

template void stableCountingSort<uint16_t>(const std::vector<uint32_t>&, const std::vector<uint16_t>&, uint32_t,
                                           std::vector<uint32_t>&, size_t);
template void stableCountingSort<uint32_t>(const std::vector<uint32_t>&, const std::vector<uint32_t>&, uint32_t,
                                           std::vector<uint32_t>&, size_t);

}  // namespace hdhair
