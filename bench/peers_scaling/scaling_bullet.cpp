// Peer Bullet bench (../shared/peers/bench_bullet.cpp, unmodified) plus scene g; see scaling_scene.hpp.
#include <btBulletDynamicsCommon.h>

#include <memory>

#include "scaling_scene.hpp"
#include "bench_bullet.cpp"
