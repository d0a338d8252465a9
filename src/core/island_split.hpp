// Splitting a big island in two, so that two threads can solve it (a pile of ragdolls is one
// island, which would otherwise take one core while the other waits).
//
// The halves are made of whole limbs: bodies that joints connect (a ragdoll) stay together, so
// no joint straddles the halves. Starting from the limb of the island's first body, limbs join
// the first half in breadth-first order over the contacts between limbs (neighbours first,
// which keeps the contacts across the cut few) until it holds half the bodies. Each half's
// joints and contacts touch only its own bodies (and static ones, which are never written), so
// the two halves can be solved at the same time; the contacts across the cut (the boundary)
// are solved first in every sweep (World's solveIsland), in two groups of whole boundary
// components (contacts joined through a body they share), one per thread: the groups touch
// disjoint bodies, so solving them at once, each in its order, gives what one thread gives
// solving the boundary in order, without one thread waiting for the other. The split depends
// only on the island, never on the thread count, so the result is the same for 1 and 2 threads.
// The first half always grows from the first body's limb: a start chosen by cut size or balance
// would flip from step to step and reorder the constraints, which makes the motion less steady.
#pragma once

#include <vector>

#include "contact.hpp"
#include "joint.hpp"

namespace ragdoll_sim {

// Offsets into the island's body, joint and contact ranges: the first half is
// [begin, *_mid), the second [*_mid, end) for bodies and joints and [contact_mid,
// boundary_begin) for contacts; [boundary_begin, contact end) are the boundary contacts, in
// groups [boundary_begin, boundary_mid) and [boundary_mid, contact end) that share no body.
struct IslandHalves {
  int body_mid = 0, joint_mid = 0, contact_mid = 0, boundary_begin = 0, boundary_mid = 0;
};

class IslandSplitter {
 public:
  // bodies[0, nb), joints[0, nj), contacts[0, nc) (indices into all_contacts): one island's.
  // Reorders the three ranges in place (stable within each half) and returns true, or returns
  // false and moves nothing when the island is a single limb. body_count: bodies in the world.
  bool split(int* bodies, int nb, Joint** joints, int nj, int* contacts, int nc,
             const std::vector<Contact>& all_contacts, int body_count, IslandHalves& out);

 private:
  int root(int i);
  template <class T, class Key>
  int stableSplit(T* items, int n, int keys, Key key, std::vector<T>& scratch);

  std::vector<int> local_;  // world body -> index in the island, -1 outside (kept all -1)
  std::vector<int> parent_, comp_, weight_, half_, offsets_, edges_, queue_;
  std::vector<int> group_;  // boundary component root -> its group (-1 unassigned)
  std::vector<int> int_scratch_;
  std::vector<Joint*> joint_scratch_;
};

}  // namespace ragdoll_sim
