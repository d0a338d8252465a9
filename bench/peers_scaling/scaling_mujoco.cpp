// Peer MuJoCo bench (../shared/peers/bench_mujoco.cpp, unmodified) plus scene g; see scaling_scene.hpp.
//
// Limit (of the peer's configuration, kept as is): the bench sets njmax = 250 rows per ragdoll,
// and MuJoCo 2.2.2 preallocates dense njmax x njmax arrays in mjData (efc_AR, efc_AR_colind) in
// one buffer whose size is an int number of bytes. From about 42 ragdolls on that exceeds 2 GiB,
// mj_makeData fails and the bench exits with "MJCF load: Error: could not create mjData".
#include <mujoco/mujoco.h>
#include <tinyxml2.h>
#include <unistd.h>

#include "scaling_scene.hpp"
#include "bench_mujoco.cpp"
