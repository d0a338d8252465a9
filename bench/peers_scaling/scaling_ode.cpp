// Peer ODE bench (../shared/peers/bench_ode.cpp, unmodified) plus scene g; see scaling_scene.hpp.
#include <ode/ode.h>

#include <array>

#include "scaling_scene.hpp"
#include "bench_ode.cpp"
