#include "gjkdem/dem/pair_state.hpp"

namespace gjkdem::dem {

// In place (both lists are sorted): drop the stale entries moving left, then
// spread the kept ones to their keys' slots from the back, where each lands
// at or after its current slot.
void align_pair_states(std::span<const PairKey> keys, std::vector<PairState>& states) {
  std::size_t kept = 0;
  for (std::size_t k = 0, i = 0; k < states.size(); ++k) {
    while (i < keys.size() && keys[i] < states[k].key) ++i;
    if (i < keys.size() && keys[i] == states[k].key) {
      states[kept++] = states[k];
      ++i;
    }
  }
  // Each key took at most one entry, so kept <= keys.size() even for a list
  // that is not sorted (a damaged checkpoint): memory stays safe.
  states.resize(keys.size());
  for (std::size_t j = keys.size(), from = kept; j-- > 0;)
    states[j] = from > 0 && states[from - 1].key == keys[j] ? states[--from] : PairState{keys[j], {}, {}, {}};
}

}  // namespace gjkdem::dem
