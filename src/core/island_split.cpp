#include "island_split.hpp"

#include <algorithm>

namespace ragdoll_sim {

int IslandSplitter::root(int i) {
  while (parent_[i] != i) i = parent_[i] = parent_[parent_[i]];
  return i;
}

// Stable reorder of items by key in [0, keys) (one pass per key; keys is 2 or 3); returns how
// many have key 0.
template <class T, class Key>
int IslandSplitter::stableSplit(T* items, int n, int keys, Key key, std::vector<T>& scratch) {
  scratch.assign(items, items + n);
  int pos = 0, first = 0;
  for (int k = 0; k < keys; ++k) {
    for (const T& t : scratch)
      if (key(t) == k) items[pos++] = t;
    if (k == 0) first = pos;
  }
  return first;
}

bool IslandSplitter::split(int* bodies, int nb, Joint** joints, int nj, int* contacts, int nc,
                           const std::vector<Contact>& all_contacts, int body_count,
                           IslandHalves& out) {
  if (int(local_.size()) < body_count) local_.resize(body_count, -1);
  for (int i = 0; i < nb; ++i) local_[bodies[i]] = i;
  // Limbs: union-find over the joints.
  parent_.resize(nb);
  for (int i = 0; i < nb; ++i) parent_[i] = i;
  for (int k = 0; k < nj; ++k) {
    const int la = local_[joints[k]->a], lb = local_[joints[k]->b];
    if (la < 0 || lb < 0) continue;
    const int ra = root(la), rb = root(lb);
    if (ra != rb) parent_[std::max(ra, rb)] = std::min(ra, rb);
  }
  comp_.assign(nb, -1);  // limb index per island body (numbered by first body)
  weight_.clear();
  for (int i = 0; i < nb; ++i) {
    const int r = root(i);
    if (comp_[r] < 0) {
      comp_[r] = int(weight_.size());
      weight_.push_back(0);
    }
    comp_[i] = comp_[r];
    ++weight_[comp_[i]];
  }
  const int limbs = int(weight_.size());
  const auto localOf = [&](int body) { return body >= 0 && body < body_count ? local_[body] : -1; };
  if (limbs > 1) {
    // Contacts between limbs as adjacency lists (a pair may appear more than once).
    offsets_.assign(limbs + 1, 0);
    const auto limbPair = [&](int ci, int& ca, int& cb) {
      const int la = localOf(all_contacts[ci].body_a), lb = localOf(all_contacts[ci].body_b);
      ca = la >= 0 ? comp_[la] : -1;
      cb = lb >= 0 ? comp_[lb] : -1;
      return ca >= 0 && cb >= 0 && ca != cb;
    };
    int ca, cb;
    for (int k = 0; k < nc; ++k)
      if (limbPair(contacts[k], ca, cb)) ++offsets_[ca + 1], ++offsets_[cb + 1];
    for (int c = 0; c < limbs; ++c) offsets_[c + 1] += offsets_[c];
    edges_.resize(offsets_[limbs]);
    queue_.assign(offsets_.begin(), offsets_.end() - 1);  // fill cursors
    for (int k = 0; k < nc; ++k)
      if (limbPair(contacts[k], ca, cb)) edges_[queue_[ca]++] = cb, edges_[queue_[cb]++] = ca;
    // Breadth-first from limb 0 until the first half holds half the bodies.
    half_.assign(limbs, 1);
    queue_.clear();
    int weight = 0, head = 0, next_unseen = 0;
    std::vector<int>& seen = parent_;  // reused: 1 once queued
    std::fill(seen.begin(), seen.begin() + limbs, 0);
    while (2 * weight < nb) {
      if (head == int(queue_.size())) {  // not reached through contacts: next limb in order
        while (seen[next_unseen]) ++next_unseen;
        seen[next_unseen] = 1;
        queue_.push_back(next_unseen);
      }
      const int c = queue_[head++];
      half_[c] = 0;
      weight += weight_[c];
      for (int e = offsets_[c]; e < offsets_[c + 1]; ++e)
        if (!seen[edges_[e]]) seen[edges_[e]] = 1, queue_.push_back(edges_[e]);
    }
  }
  // The first half may have taken every limb (one big limb and small ones).
  const bool split =
      limbs > 1 && std::any_of(half_.begin(), half_.begin() + limbs, [](int h) { return h; });
  if (split) {
    const auto halfOf = [&](int body) {
      const int l = localOf(body);
      return l >= 0 ? half_[comp_[l]] : -1;
    };
    // Keys are read through local_, so the bodies are reordered last.
    const auto jointHalf = [&](Joint* j) {
      const int h = halfOf(j->a);
      return h >= 0 ? h : std::max(0, halfOf(j->b));
    };
    out.joint_mid = stableSplit(joints, nj, 2, jointHalf, joint_scratch_);
    const auto contactKey = [&](int ci) {
      const int ha = halfOf(all_contacts[ci].body_a), hb = halfOf(all_contacts[ci].body_b);
      if (ha < 0) return std::max(0, hb);
      if (hb < 0 || ha == hb) return ha;
      return 2;
    };
    out.contact_mid = stableSplit(contacts, nc, 3, contactKey, int_scratch_);
    int second = 0;
    for (int k = out.contact_mid; k < nc && contactKey(contacts[k]) == 1; ++k) ++second;
    out.boundary_begin = out.contact_mid + second;
    // Boundary components: union-find over the island's bodies (both bodies of a boundary
    // contact are in the island; parent_ and weight_ reused). Each component goes whole, in
    // the order of its first contact, to the group with fewer contacts so far.
    int* boundary = contacts + out.boundary_begin;
    const int nbc = nc - out.boundary_begin;
    for (int i = 0; i < nb; ++i) parent_[i] = i;
    const auto bodyRoot = [&](int ci) { return root(localOf(all_contacts[ci].body_a)); };
    for (int k = 0; k < nbc; ++k) {
      const Contact& c = all_contacts[boundary[k]];
      const int ra = root(localOf(c.body_a)), rb = root(localOf(c.body_b));
      if (ra != rb) parent_[std::max(ra, rb)] = std::min(ra, rb);
    }
    weight_.assign(nb, 0);  // now contacts per component root
    for (int k = 0; k < nbc; ++k) ++weight_[bodyRoot(boundary[k])];
    group_.assign(nb, -1);
    int load[2] = {0, 0};
    for (int k = 0; k < nbc; ++k) {
      const int r = bodyRoot(boundary[k]);
      if (group_[r] >= 0) continue;
      group_[r] = load[1] < load[0] ? 1 : 0;
      load[group_[r]] += weight_[r];
    }
    out.boundary_mid = out.boundary_begin +
                       stableSplit(boundary, nbc, 2, [&](int ci) { return group_[bodyRoot(ci)]; },
                                   int_scratch_);
    out.body_mid = stableSplit(bodies, nb, 2, halfOf, int_scratch_);
  }
  for (int i = 0; i < nb; ++i) local_[bodies[i]] = -1;
  return split;
}

}  // namespace ragdoll_sim
