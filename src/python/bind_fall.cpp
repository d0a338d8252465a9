// The fall recorder's binding (ragdoll_sim.batch).
#include "bindings.hpp"

namespace ragdoll_sim {
namespace python {

void bindFall(pybind11::module_& m) {}

}  // namespace python
}  // namespace ragdoll_sim
