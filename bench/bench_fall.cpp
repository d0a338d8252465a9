// bench_fall: the single-run rate of a fall study, one 3 s fall of the bundled ragdoll down
// worlds/stairs.world as launch/stairs.launch spawns it, plus a 40 N s push on the torso, run
// by runFall (fall_run.hpp) with the model and world parsed once, as ragdoll_batch's runner
// does. Prints seconds per fall (median of --runs) and the runs per minute that makes.
//   bench_fall [--runs N] [--steps S] [--world PATH|none] [--urdf PATH]
// bench/fall_3s.yaml is the same fall as a ragdoll_batch scenario (docs/benchmarks.md).
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <memory>
#include <string>
#include <vector>

#include "ragdoll_sim/fall_run.hpp"
#include "ragdoll_sim/urdf_loader.hpp"
#include "ragdoll_sim/world_file.hpp"

using namespace ragdoll_sim;

int main(int argc, char** argv) {
  int runs = 10;
  long steps = 3000;
  std::string world_path = std::string(RAGDOLL_SIM_SOURCE_DIR) + "/worlds/stairs.world";
  std::string urdf = std::string(RAGDOLL_SIM_SOURCE_DIR) + "/urdf/ragdoll.urdf";
  for (int i = 1; i + 1 < argc; i += 2) {
    if (!std::strcmp(argv[i], "--runs")) runs = std::atoi(argv[i + 1]);
    else if (!std::strcmp(argv[i], "--steps")) steps = std::atol(argv[i + 1]);
    else if (!std::strcmp(argv[i], "--world")) world_path = argv[i + 1];
    else if (!std::strcmp(argv[i], "--urdf")) urdf = argv[i + 1];
    else {
      std::fprintf(stderr, "bench_fall: unknown option %s\n", argv[i]);
      return 1;
    }
  }
  const UrdfLoadResult model = loadUrdfFile(urdf);
  if (!model.ok) {
    std::fprintf(stderr, "bench_fall: %s: %s\n", urdf.c_str(), model.error.c_str());
    return 1;
  }
  FallRunDef d;
  d.model = std::make_shared<const RagdollDef>(model.def);
  if (world_path != "none") {
    const WorldLoadResult w = loadWorldFile(world_path);
    if (!w.ok) {
      std::fprintf(stderr, "bench_fall: %s: %s\n", world_path.c_str(), w.error.c_str());
      return 1;
    }
    d.world = std::make_shared<const WorldFileDef>(w.def);
  }
  const Material surface{0.8, 0.8, 0.1, defaultSurface().rolling_resistance};
  d.scene.material = d.scene.ragdoll_surface = d.scene.ground_surface = d.scene.object_surface =
      surface;
  d.pose = Transform(Vec3(-0.2, 0.0, 2.56), Quat::Identity());
  d.linear_velocity = Vec3(1.0, 0.0, 0.0);
  d.angular_velocity = Vec3(0.0, 1.0, 0.0);
  d.push_link = "torso";
  d.push_impulse = Vec3(40.0, 0.0, 0.0);
  d.steps = steps;
  std::vector<double> seconds;
  FallRecord last;
  for (int r = 0; r < runs; ++r) {
    const auto t0 = std::chrono::steady_clock::now();
    last = runFall(d);
    seconds.push_back(std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count());
  }
  std::sort(seconds.begin(), seconds.end());
  const double median = seconds[seconds.size() / 2];
  std::printf("bench_fall runs=%d steps=%ld s_per_fall_median=%.4f s_per_fall_min=%.4f "
              "runs_per_min=%.1f hic15=%.1f rest=%s time_to_rest=%.3f\n",
              runs, steps, median, seconds.front(), 60.0 / median, last.hic15,
              restClassName(last.rest), last.time_to_rest);
  return 0;
}
