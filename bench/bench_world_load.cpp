// bench_world_load: scene l of `make bench`, the load time of a generated SDF world of dynamic
// primitives. N models (--objects, default 3000), each one link with an <inertial>, a
// <collision> and a <visual>: boxes, spheres and cylinders in turn, each kind in --sizes
// different sizes (default 8), on a square grid with 1 m pitch, 0.5 m above the ground.
// Models that differ only in name and pose are parsed once (world_loader.cpp), so the sizes
// decide how many models SDFormat itself reads; --sizes 0 gives every model its own size (and
// SDFormat's memory per model makes the loader refuse such a world of 3000: max_sdf_megabytes).
//   parse_s: loadWorldString (text -> WorldFileDef); build_s: Scene::loadWorld into a started
//   Scene (each model an object: its checks, bodies and shapes in the World);
//   load_s = parse_s + build_s; first_step_s: the first Scene::step after it.
// One line: engine=ragdoll_sim scenario=l objects=N ... (as bench_ragdoll's lines).
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <string>

#include "ragdoll_sim/scene.hpp"
#include "ragdoll_sim/world_file.hpp"

using namespace ragdoll_sim;

namespace {

double seconds(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

// The world's text: model k is kind k % 3 in size (k / 3) % sizes (or k with sizes 0).
std::string worldText(int objects, int sizes) {
  const int cols = int(std::ceil(std::sqrt(double(objects))));
  std::string s = "<?xml version=\"1.0\"?>\n<sdf version=\"1.7\"><world name=\"primitives\">\n";
  char buf[1024];
  for (int k = 0; k < objects; ++k) {
    const int variant = sizes > 0 ? (k / 3) % sizes : k;
    const double a = 0.2 + 0.3 * (sizes > 0 ? variant / double(sizes) : variant / double(objects));
    std::string geometry;
    double ixx, izz;
    const double m = 1.0;
    if (k % 3 == 0) {
      std::snprintf(buf, sizeof buf, "<box><size>%.6f %.6f %.6f</size></box>", a, a, a);
      ixx = izz = m * a * a / 6.0;
    } else if (k % 3 == 1) {
      std::snprintf(buf, sizeof buf, "<sphere><radius>%.6f</radius></sphere>", 0.5 * a);
      ixx = izz = 0.4 * m * 0.25 * a * a;
    } else {
      std::snprintf(buf, sizeof buf, "<cylinder><radius>%.6f</radius><length>%.6f</length></cylinder>",
                    0.5 * a, a);
      ixx = m * (3 * 0.25 * a * a + a * a) / 12.0;
      izz = 0.5 * m * 0.25 * a * a;
    }
    geometry = buf;
    const double x = (k % cols - 0.5 * (cols - 1)) * 1.0, y = (k / cols - 0.5 * (cols - 1)) * 1.0;
    std::snprintf(buf, sizeof buf,
                  "<model name=\"obj_%d\"><pose>%.3f %.3f 0.5 0 0 0</pose><link name=\"link\">"
                  "<inertial><mass>%g</mass><inertia><ixx>%.9f</ixx><iyy>%.9f</iyy><izz>%.9f</izz>"
                  "<ixy>0</ixy><ixz>0</ixz><iyz>0</iyz></inertia></inertial>",
                  k, x, y, m, ixx, ixx, izz);
    s += buf;
    s += "<collision name=\"collision\"><geometry>" + geometry + "</geometry></collision>";
    s += "<visual name=\"visual\"><geometry>" + geometry + "</geometry></visual></link></model>\n";
  }
  return s + "</world></sdf>\n";
}

}  // namespace

int main(int argc, char** argv) {
  int objects = 3000, sizes = 8;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    if (a == "--objects" && i + 1 < argc) objects = std::atoi(argv[++i]);
    else if (a == "--sizes" && i + 1 < argc) sizes = std::atoi(argv[++i]);
    else if (a == "l") continue;
    else {
      std::fprintf(stderr, "usage: %s [l] [--objects N] [--sizes K (0: all different)]\n", argv[0]);
      return 2;
    }
  }
  if (objects < 1 || sizes < 0) {
    std::fprintf(stderr, "bench_world_load: --objects must be >= 1 and --sizes >= 0\n");
    return 2;
  }
  const std::string text = worldText(objects, sizes);

  auto t0 = std::chrono::steady_clock::now();
  const WorldLoadResult loaded = loadWorldString(text);
  const double parse_s = seconds(t0);
  if (!loaded.ok) {
    std::fprintf(stderr, "bench_world_load: %s\n", loaded.error.c_str());
    return 1;
  }

  t0 = std::chrono::steady_clock::now();
  Scene scene{SceneDef()};
  std::string error;
  if (!scene.start(&error) || !scene.loadWorld(loaded.def, &error)) {
    std::fprintf(stderr, "bench_world_load: %s\n", error.c_str());
    return 1;
  }
  const double build_s = seconds(t0);
  const int bodies = scene.world().bodyCount();

  t0 = std::chrono::steady_clock::now();
  scene.step();
  const double first_step_s = seconds(t0);

  std::printf("engine=ragdoll_sim scenario=l objects=%d sizes=%d bodies=%d sdf_bytes=%zu "
              "parse_s=%.3f build_s=%.3f load_s=%.3f first_step_s=%.4f\n",
              objects, sizes, bodies, text.size(), parse_s, build_s, parse_s + build_s,
              first_step_s);
  return 0;
}
