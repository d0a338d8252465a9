// How the AVX-512F builds of the kernel files walk a range of 8-lane blocks: two blocks of a
// colour at once where they can go together. Included by the kernel files, so it includes
// nothing (see lanes.hpp for why).
#pragma once

namespace ragdoll_sim {

// In order: runs of blocks that go alone to alone(first, n), and each pair k, k + 1 with
// pairs(blocks[k], blocks[k + 1]) to pair(blocks[k]).
template <class Block, class Pairs, class Alone, class Pair>
void byPairs(Block* blocks, int count, Pairs pairs, Alone alone, Pair pair) {
  for (int k = 0; k < count;) {
    int j = k;
    while (j < count && !(j + 1 < count && pairs(blocks[j], blocks[j + 1]))) ++j;
    if (j > k) alone(blocks + k, j - k);
    if (j < count) pair(blocks[j]);
    k = j + 2;
  }
}

}  // namespace ragdoll_sim
