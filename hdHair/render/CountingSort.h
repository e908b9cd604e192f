#pragma once
// A stable counting sort (LSD radix sort's pass) that runs on all cores:
// the input is cut into blocks, each block counts its keys, one exclusive
// prefix sum over (key, block) in key-major order gives every block its own
// start in each key's run, and the blocks scatter in parallel. Blocks keep
// input order inside a key's run, and the prefix sum orders blocks as the
// input does, so the result equals a serial stable sort's. O(n + keys x
// blocks) work, O(keys x blocks) extra memory.

#include <cstddef>
#include <cstdint>
#include <vector>

namespace hdhair {

// Writes `in` to `out` ordered by key[in[i]] ascending (every key below
// `keyCount`), equal keys in input order. `blocks`: how many parts run in
// parallel; 0 chooses from the size and the machine, 1 is serial.
template <typename Key>
void stableCountingSort(const std::vector<uint32_t>& in, const std::vector<Key>& key, uint32_t keyCount,
                        std::vector<uint32_t>& out, size_t blocks = 0);

extern template void stableCountingSort<uint16_t>(const std::vector<uint32_t>&, const std::vector<uint16_t>&, uint32_t,
                                                  std::vector<uint32_t>&, size_t);
extern template void stableCountingSort<uint32_t>(const std::vector<uint32_t>&, const std::vector<uint32_t>&, uint32_t,
                                                  std::vector<uint32_t>&, size_t);

}  // namespace hdhair
