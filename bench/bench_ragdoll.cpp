// bench_ragdoll: our engine on the peer scenes (../shared/peers/README.md), same result line.
//   a: 1 ragdoll standing, pelvis at 1.5 m, 10 000 steps
//   b: 32 ragdolls standing on a 4 x 8 grid, 1.5 m pitch, 3 000 steps
//   c: 8 ragdolls prone (pitch 90 deg), yaw k*45 deg, pelvis at 1.5 + 0.6 k, 5 000 steps
//   g: scaling, --ragdolls N (default 1) standing like b on a grid with 1.5 m pitch (ceil(sqrt N)
//      columns, centred; scaling_grid.hpp, shared with bench/peers_scaling), 3 000 steps
//   p: pile, 64 ragdolls dropped prone in 16 layers of 4 into a 3 m x 3 m pit (3 m walls), so
//      they land on each other, 8 000 steps; its line adds pit_outside_end (pelvis outside the
//      walls at the end) and pelvis_z_end_max (height of the pile);
//   s: sleep check, a 4 x 4 x 3 pile of 0.4 m boxes, 3 000 steps
//   f, w, v: scale of static worlds, 1 ragdoll standing as in a (pelvis at 1.5 m), sleep off
//      (every step a full one), 5 000 steps: f on the plane alone; w among 10 000 static boxes,
//      each its own body; v the same boxes as shapes of one static body (static_world.hpp)
//   Every line also gives the cost per step in the first and the last second (p, s: asleep).
// `bench_ragdoll sync` prints what two threads' handoffs cost and how fast the two cores run at
// once instead (sync_probe.hpp).
// dt = 1 ms, gravity -9.81 z, ground z = 0, friction 0.8. Only World::step is timed. The
// metrics are computed here from link poses and the URDF joint data alone (anchor error,
// ground penetration of the analytic shapes, joint angles vs limits, rest state at 3 s).
#include <array>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <memory>
#include <string>

#include "joint_angles.hpp"
#include "ragdoll_sim/state_hash.hpp"
#include "ragdoll_sim/urdf_loader.hpp"
#include "scaling_grid.hpp"
#include "static_world.hpp"
#include "sync_probe.hpp"
#include "world_tuning.hpp"

using namespace ragdoll_sim;

namespace {

// --opt profile=1's fields, in the line's order.
constexpr std::array<double StepProfile::*, 10> kProfileFields = {
    &StepProfile::step,    &StepProfile::guard,   &StepProfile::collide,
    &StepProfile::boxes,   &StepProfile::pairs,   &StepProfile::narrowphase,
    &StepProfile::islands, &StepProfile::solve,   &StepProfile::finish,
    &StepProfile::solve_wait};
constexpr std::array<const char*, 10> kProfileNames = {
    "step", "guard", "collide", "boxes", "pairs", "narrowphase", "islands", "solve", "finish",
    "solve_wait"};

struct Scene {
  char id;
  int steps;
  std::vector<Transform> roots;
  std::vector<std::pair<Vec3, Vec3>> walls;  // static boxes: centre, half extents
  std::vector<Vec3> boxes;                   // dynamic 0.4 m boxes, 1 kg: centres
  int static_boxes = 0;  // static_world.hpp: 0 none, 1 one body each, 2 shapes of one body
  bool sleep = true;     // false: sleep off unless --opt sleep says otherwise
};

Scene makeScene(char id, int ragdolls) {
  Scene s{id, 0, {}, {}, {}, 0, true};
  if (id == 'a') {
    s.steps = 10000;
    s.roots.push_back({Vec3(0, 0, 1.5), Quat::Identity()});
  } else if (id == 'b') {
    s.steps = 3000;
    for (int i = 0; i < 4; ++i)
      for (int j = 0; j < 8; ++j) s.roots.push_back({Vec3((i - 1.5) * 1.5, (j - 3.5) * 1.5, 1.5), Quat::Identity()});
  } else if (id == 'c') {
    s.steps = 5000;
    for (int k = 0; k < 8; ++k) s.roots.push_back({Vec3(0, 0, 1.5 + 0.6 * k), quatFromRpy(0, M_PI / 2, k * M_PI / 4)});
  } else if (id == 'g') {
    s.steps = scaling::kDefaultSteps;
    for (const auto& xyz : scaling::gridRoots(ragdolls))
      s.roots.push_back({Vec3(xyz[0], xyz[1], xyz[2]), Quat::Identity()});
  } else if (id == 'p') {
    s.steps = 8000;
    for (int k = 0; k < 16; ++k)
      for (int i = 0; i < 4; ++i) {
        const double off = (i - 1.5) * 0.7, yaw = (k % 2) * M_PI / 2 + (i % 2) * M_PI;
        const Vec3 p = k % 2 ? Vec3(off, 0.0, 0.6 + 0.45 * k) : Vec3(0.0, off, 0.6 + 0.45 * k);
        s.roots.push_back({p, quatFromRpy(0, M_PI / 2, yaw)});
      }
    for (int side = 0; side < 4; ++side) {
      const double sign = side % 2 ? 1.0 : -1.0;
      const bool along_x = side < 2;
      const Vec3 c = along_x ? Vec3(sign * 1.6, 0, 1.5) : Vec3(0, sign * 1.6, 1.5);
      const Vec3 h = along_x ? Vec3(0.1, 1.7, 1.5) : Vec3(1.7, 0.1, 1.5);
      s.walls.emplace_back(c, h);
    }
  } else if (id == 's') {
    s.steps = 3000;
    for (int i = 0; i < 4; ++i)
      for (int j = 0; j < 4; ++j)
        for (int k = 0; k < 3; ++k) s.boxes.emplace_back(i * 0.45, j * 0.45, 0.2 + 0.45 * k);
  } else if (id == 'f' || id == 'w' || id == 'v') {
    s.steps = 5000;
    s.roots.push_back({Vec3(0, 0, 1.5), Quat::Identity()});
    s.static_boxes = id == 'w' ? 1 : id == 'v' ? 2 : 0;
    s.sleep = false;
  } else {
    std::fprintf(stderr, "scenario must be a, b, c, f, g, p, s, v or w\n");
    std::exit(2);
  }
  return s;
}

double lowestZ(const Geometry& g, const Transform& x) {
  const Mat3 R = x.q.toRotationMatrix();
  const double cz = x.p.z();
  switch (g.type) {
    case ShapeType::Sphere: return cz - g.radius;
    case ShapeType::Box: return cz - R.row(2).cwiseAbs().dot(g.half_extents);
    case ShapeType::Capsule: return cz - g.half_height * std::abs(R(2, 2)) - g.radius;
    case ShapeType::Cylinder: {
      const double az = std::abs(R(2, 2));
      return cz - g.half_height * az - g.radius * std::sqrt(std::max(0.0, 1 - az * az));
    }
    default: return cz;
  }
}

struct Metrics {
  double max_anchor = 0, max_pen = 0, max_limit = 0;
  std::string worst_joint = "-", pen_link = "-", anchor_joint = "-";
  int worst_step = -1, pen_step = -1, anchor_step = -1;
  bool nan = false;
  double pel_mean = NAN, pel_min = NAN, pel_max = NAN, pen3 = NAN, anchor3 = NAN, vmax3 = NAN;
  std::vector<Vec3> prev;

  void sample(const RagdollDef& def, const std::vector<Transform>& poses, int n, int step,
              double dt, int step3) {
    const size_t L = def.links.size();
    double pen = 0, anchor = 0, lim = 0;
    const RagdollJointDef* wj = nullptr;
    const RagdollJointDef* aj = nullptr;
    const std::string* pen_name = nullptr;
    for (const Transform& p : poses)
      if (!p.p.allFinite() || !p.q.coeffs().allFinite()) nan = true;
    for (int r = 0; r < n; ++r) {
      const Transform* W = &poses[r * L];
      for (size_t i = 0; i < L; ++i)
        for (const ShapeDef& s : def.links[i].shapes) {
          const double d = -lowestZ(s.geometry, W[i] * s.local);
          if (d > pen) pen = d, pen_name = &def.links[i].name;
        }
      for (const RagdollJointDef& j : def.joints) {
        const Transform fa = W[j.parent] * j.frame_parent, fb = W[j.child] * j.frame_child;
        const double a = (fb.p - fa.p).norm();
        if (a > anchor) anchor = a, aj = &j;
        double v = 0;
        if (j.kind == RagdollJointKind::Hinge) {
          const double q = hingeAngle(fa.q, fb.q, j.axes[0]);
          v = std::max(j.lower[0] - q, q - j.upper[0]);
        } else {
          const Vec3 q = EulerBasis({j.axes[0], j.axes[1], j.axes[2]}).angles(fa.q, fb.q);
          for (int k = 0; k < 3; ++k) v = std::max({v, j.lower[k] - q[k], q[k] - j.upper[k]});
        }
        if (v > lim) {
          lim = v;
          wj = &j;
        }
      }
    }
    if (pen > max_pen) {
      max_pen = pen;
      pen_link = *pen_name;
      pen_step = step;
    }
    if (anchor > max_anchor) {
      max_anchor = anchor;
      anchor_joint = aj->name;
      anchor_step = step;
    }
    if (lim > max_limit) {
      max_limit = lim;
      worst_joint = wj->name;
      worst_step = step;
    }
    if (step == step3 - 1) {
      prev.clear();
      for (const Transform& p : poses) prev.push_back(p.p);
    }
    if (step == step3) {
      pen3 = pen;
      anchor3 = anchor;
      double s = 0, mn = 1e300, mx = -1e300;
      for (int r = 0; r < n; ++r) {
        const double z = poses[r * L].p.z();
        s += z;
        mn = std::min(mn, z);
        mx = std::max(mx, z);
      }
      if (n > 0) {  // scene s has no ragdolls: the pelvis fields stay nan
        pel_mean = s / n;
        pel_min = mn;
        pel_max = mx;
      }
      vmax3 = 0;
      for (size_t i = 0; i < poses.size() && i < prev.size(); ++i)
        vmax3 = std::max(vmax3, (poses[i].p - prev[i]).norm() / dt);
    }
  }
};

// --urdf's default, from the build folder (scripts/bench.sh runs there).
constexpr const char* kDefaultUrdf = "../shared/peers/ragdoll15.urdf";

// The scene in `world`: the ground, the ragdolls (each root turned `yaw` about z), the walls, the
// static boxes, the dynamic boxes; friction 0.8 and `rolling` resistance everywhere.
std::vector<Ragdoll> populate(World& world, const Scene& sc, const RagdollDef& def, double yaw,
                              double rolling) {
  BodyDef ground;
  ground.type = BodyType::Static;
  Material mat;
  mat.static_friction = mat.kinetic_friction = 0.8;
  mat.rolling_resistance = rolling;
  world.addShape(world.createBody(ground), {Geometry::plane(Vec3::UnitZ(), 0.0), Transform(), mat});
  std::vector<Ragdoll> ragdolls;
  for (const Transform& root : sc.roots)
    ragdolls.push_back(spawnRagdoll(
        world, def, {root.p, Quat(Eigen::AngleAxisd(yaw, Vec3::UnitZ())) * root.q}, &mat));
  for (const auto& [centre, half] : sc.walls) {
    BodyDef wall;
    wall.type = BodyType::Static;
    wall.pose.p = centre;
    world.addShape(world.createBody(wall), {Geometry::box(half), Transform(), mat});
  }
  if (sc.static_boxes) static_world::addBoxes(world, sc.static_boxes == 2, mat);
  for (const Vec3& c : sc.boxes) {
    BodyDef box;
    box.pose.p = c;
    box.inertia = Mat3::Identity() * (1.0 / 6.0) * 0.4 * 0.4;
    world.addShape(world.createBody(box), {Geometry::box(Vec3::Constant(0.2)), Transform(), mat});
  }
  return ragdolls;
}

// `bench_ragdoll sync`: the handoffs, and the cores' speed on the solver's own work: a world of
// scene g with 8 ragdolls for each of two threads, stepped on that thread alone, sleep off
// (sync_probe.hpp).
int syncProbe(const std::string& urdf) {
  const UrdfLoadResult loaded = loadUrdfFile(urdf);
  if (!loaded.ok) {
    std::fprintf(stderr, "bench_ragdoll: %s\n", loaded.error.c_str());
    return 1;
  }
  WorldDef wd;
  wd.threads = 1;
  wd.sleep.enabled = false;
  const Scene sc = makeScene('g', 8);
  std::vector<std::unique_ptr<World>> worlds;
  for (int t = 0; t < 2; ++t) {
    worlds.push_back(std::make_unique<World>(wd));
    populate(*worlds.back(), sc, loaded.def, 0.0, 0.0);
  }
  const SyncCost c = measureSync([&](int t, int steps) {
    for (int k = 0; k < steps; ++k) worlds[size_t(t)]->step(1e-3);
  });
  std::printf("region_us=%.3f barrier_us=%.3f core0=%.3f core1=%.3f ceiling=%.2f\n",
              c.region_us, c.barrier_us, c.core_speed[0], c.core_speed[1], c.ceiling);
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  if (argc >= 2 && std::strcmp(argv[1], "sync") == 0) {
    std::string urdf = kDefaultUrdf;
    if (argc == 4 && std::strcmp(argv[2], "--urdf") == 0) urdf = argv[3];
    else if (argc != 2) {
      std::fprintf(stderr, "usage: %s sync [--urdf F]\n", argv[0]);
      return 2;
    }
    return syncProbe(urdf);
  }
  char scenario = 'a';
  int steps = -1, n_ragdolls = -1;
  WorldDef wd;
  // --opt cache_distance, range_reserve, lane_exact_angles, keep_schedule (internal:
  // world_tuning.hpp)
  WorldTuning tuning;
  bool metrics = true;
  double rolling = 0.0;
  double yaw = 0.0;  // --opt yaw=R: every root turned R rad about z (round-off variants of a scene)
  // --opt hash=1: the line ends with state_hash, an FNV-1a hash of every body's pose and
  // velocity bits after every step, so that a change meant to keep the results can be checked
  // bit for bit.
  bool hash = false;
  bool sleep_given = false;  // --opt sleep: overrides the scene's own setting
  int trace = 0;  // --opt trace=N: every N steps, awake bodies, islands, mean step time (stderr)
  // --opt joint_damping=D,joint_friction=F: every joint axis gets viscous damping D (N m s/rad)
  // and Coulomb friction F (N m), as a URDF <dynamics> on every joint would give (ragdoll15 has
  // none; a what-if for the rest speed, not part of the peers' scenes)
  double joint_damping = 0.0, joint_friction = 0.0;
  // --opt track=1: contact impulse tracking on; reports=1: and World::contactReports after
  // every step, timed with it (what a contacts subscriber costs the loop)
  bool track = false, reports = false;
  // --opt profile=1: World::stepProfile's phases, mean µs per step, at the end of the line
  bool profile = false;
  std::string urdf = kDefaultUrdf;
  for (int i = 1; i < argc; ++i) {
    const std::string s = argv[i];
    if (s == "--steps" && i + 1 < argc) steps = std::atoi(argv[++i]);
    else if (s == "--ragdolls" && i + 1 < argc) n_ragdolls = std::atoi(argv[++i]);
    else if (s == "--urdf" && i + 1 < argc) urdf = argv[++i];
    else if (s == "--opt" && i + 1 < argc) {
      // comma-separated key=value solver settings
      std::string opts = argv[++i];
      for (size_t b = 0; b < opts.size();) {
        size_t e = opts.find(',', b);
        if (e == std::string::npos) e = opts.size();
        const std::string kv = opts.substr(b, e - b);
        const size_t eq = kv.find('=');
        const std::string k = kv.substr(0, eq);
        const double v = eq == std::string::npos ? 1.0 : std::atof(kv.c_str() + eq + 1);
        if (k == "substeps") wd.solver.substeps = int(v);
        else if (k == "joint_hertz") wd.solver.joint_hertz = v;
        else if (k == "joint_zeta") wd.solver.joint_damping_ratio = v;
        else if (k == "contact_hertz") wd.solver.contact_hertz = v;
        else if (k == "contact_zeta") wd.solver.contact_damping_ratio = v;
        else if (k == "sleep") {
          wd.sleep.enabled = v != 0.0;
          sleep_given = true;
        }
        else if (k == "threads") wd.threads = int(v);
        else if (k == "position_iterations") wd.solver.position_iterations = int(v);
        else if (k == "anchor_iterations") wd.solver.anchor_iterations = int(v);
        else if (k == "exact_joints") wd.solver.exact_joints = v != 0.0;
        else if (k == "lanes") wd.solver.lanes = int(v);
        else if (k == "relax") wd.solver.contact_relax_iterations = int(v);
        else if (k == "joint_relax") wd.solver.joint_relax_iterations = int(v);
        else if (k == "sleep_speed") wd.sleep.speed = v;
        else if (k == "island_speed") wd.sleep.island_speed = v;
        else if (k == "time_to_sleep") wd.sleep.time = v;
        else if (k == "rest_substeps") wd.sleep.rest_substeps = int(v);
        else if (k == "rest_time") wd.sleep.rest_time = v;
        else if (k == "rest_relax") wd.sleep.rest_relax_iterations = int(v);
        else if (k == "static_friction_speed") wd.solver.static_friction_speed = v;
        else if (k == "joint_slop") wd.solver.joint_slop = v;
        else if (k == "angular_slop") wd.solver.angular_slop = v;
        else if (k == "speculative") wd.solver.speculative_distance = v;
        else if (k == "cache_distance") tuning.manifold_cache_distance = v;
        else if (k == "range_reserve") tuning.range_reserve = int(v);
        else if (k == "lane_exact_angles") tuning.lane_exact_angles = v != 0.0;
        else if (k == "keep_schedule") tuning.keep_schedule = v != 0.0;
        else if (k == "rolling") rolling = v;
        else if (k == "yaw") yaw = v;
        else if (k == "trace") trace = int(v);
        else if (k == "hash") hash = v != 0.0;
        else if (k == "joint_damping") joint_damping = v;
        else if (k == "joint_friction") joint_friction = v;
        else if (k == "track") track = v != 0.0;
        else if (k == "reports") reports = track = v != 0.0;
        else if (k == "profile") profile = v != 0.0;
        else {
          std::fprintf(stderr, "unknown option %s\n", k.c_str());
          return 2;
        }
        b = e + 1;
      }
    }
    else if (s == "--no-metrics") metrics = false;
    else if (s.size() == 1 && std::string("abcfgpsvw").find(s[0]) != std::string::npos) scenario = s[0];
    else {
      std::fprintf(stderr, "usage: %s a|b|c|f|g|p|s|v|w [--ragdolls N (g only)] [--steps N] [--urdf F] [--no-metrics] [--opt substeps=4,joint_hertz=240,contact_hertz=240,sleep=1,...]\n", argv[0]);
      return 2;
    }
  }
  if (const std::string e = worldDefError(wd) + worldTuningError(tuning); !e.empty()) {
    std::fprintf(stderr, "bench_ragdoll: --opt: %s\n", e.c_str());
    return 2;
  }
  if (n_ragdolls >= 0 && scenario != 'g') {
    std::fprintf(stderr, "bench_ragdoll: --ragdolls is only for scene g\n");
    return 2;
  }
  if (scenario == 'g' && n_ragdolls < 0) n_ragdolls = 1;
  if (scenario == 'g' && n_ragdolls < 1) {
    std::fprintf(stderr, "bench_ragdoll: --ragdolls must be >= 1\n");
    return 2;
  }
  const UrdfLoadResult loaded = loadUrdfFile(urdf);
  if (!loaded.ok) {
    std::fprintf(stderr, "bench_ragdoll: %s\n", loaded.error.c_str());
    return 1;
  }
  RagdollDef def = loaded.def;
  if (joint_damping > 0.0 || joint_friction > 0.0)
    for (RagdollJointDef& j : def.joints) {
      j.damping.assign(j.axes.size(), joint_damping);
      j.friction.assign(j.axes.size(), joint_friction);
    }
  const Scene sc = makeScene(scenario, n_ragdolls);
  if (steps < 0) steps = sc.steps;
  const int n = int(sc.roots.size());
  const double dt = 1e-3;
  if (!sc.sleep && !sleep_given) wd.sleep.enabled = false;

  World world(wd);
  WorldInternals::setTuning(world, tuning);
  world.setContactImpulseTracking(track);
  std::vector<ContactReport> contact_reports;
  size_t reported_points = 0;  // summed over the steps, so the reports cannot be optimised away
  const std::vector<Ragdoll> ragdolls = populate(world, sc, def, yaw, rolling);

  Metrics m;
  std::vector<Transform> poses(n * def.links.size());
  double wall = 0.0, wall_first = 0.0, wall_last = 0.0, wall_trace = 0.0;
  // Bodies awake after each step, summed over the run (outside the timed calls): what sleeping
  // left to solve. Deterministic for a given binary and scene, unlike the wall time, it tells a
  // change that only moves when the ragdolls sleep (a change of round-off can: docs/benchmarks.md)
  // from one that changes the cost of a step.
  long awake_body_steps = 0;
  long resting_body_steps = 0;  // of those, in islands on the rest substeps (SleepDef::rest_substeps)
  uint64_t state_hash = kFnvOffsetBasis;
  const int window = std::min(1000, steps);
  world.setProfiling(profile);
  StepProfile phases;  // summed over the steps
  struct {
    long lane_batches = 0, contact_lane_rows = 0, contact_lanes = 0, joint_lane_rows = 0,
         joint_lanes = 0;
  } lanes;  // IslandCounters' wide solver fields, summed over the steps (profile=1)
  const auto loop0 = std::chrono::steady_clock::now();
  for (int step = 1; step <= steps; ++step) {
    const auto t0 = std::chrono::steady_clock::now();
    world.step(dt);
    if (reports) {
      world.contactReports(contact_reports);
      for (const ContactReport& r : contact_reports) reported_points += size_t(r.count);
    }
    const double dt_wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    wall += dt_wall;
    if (step <= window) wall_first += dt_wall;
    if (step > steps - window) wall_last += dt_wall;
    wall_trace += dt_wall;
    if (hash) state_hash = hashStates(world, state_hash);
    const IslandCounters counters = world.islandCounters();
    if (profile) {
      const StepProfile& p = world.stepProfile();
      for (double StepProfile::*f : kProfileFields) phases.*f += p.*f;
      lanes.lane_batches += counters.lane_batches;
      lanes.contact_lane_rows += counters.contact_lane_rows;
      lanes.contact_lanes += counters.contact_lanes;
      lanes.joint_lane_rows += counters.joint_lane_rows;
      lanes.joint_lanes += counters.joint_lanes;
    }
    awake_body_steps += world.awakeBodyCount();
    resting_body_steps += counters.resting_bodies;
    if (trace > 0 && step % trace == 0) {
      // fastest ragdoll link: COM speed and angular speed (what sleeping compares)
      // and the mechanical energy (kinetic + potential in the scene's gravity) of the ragdolls
      double vmax = 0.0, wmax = 0.0, pe = 0.0;
      size_t vr = 0, vi = 0, wr = 0, wi = 0;  // ragdoll and link of each maximum
      for (size_t r = 0; r < ragdolls.size(); ++r)
        for (size_t i = 0; i < ragdolls[r].bodies.size(); ++i) {
          const BodyId b = ragdolls[r].bodies[i];
          const BodyState st = world.bodyState(b);
          pe -= world.bodyDef(b).mass * wd.gravity.dot(st.com_position);
          const double v = st.linear_velocity.norm(), w = st.angular_velocity.norm();
          if (v > vmax) vmax = v, vr = r, vi = i;
          if (w > wmax) wmax = w, wr = r, wi = i;
        }
      const IslandCounters isl = world.islandCounters();
      std::fprintf(stderr,
                   "trace step=%d awake=%d us_per_step=%.1f vmax=%.4g (%zu#%s) wmax=%.4g (%zu#%s) "
                   "energy_j=%.2f islands=%d split=%d largest=%d contacts=%d\n",
                   step, world.awakeBodyCount(), 1e6 * wall_trace / trace, vmax, vr,
                   def.links[vi].name.c_str(), wmax, wr, def.links[wi].name.c_str(),
                   world.kineticEnergy() + pe, isl.islands, isl.split_islands, isl.largest_island,
                   isl.contacts);
      wall_trace = 0.0;
    }
    if (metrics || step == 2999 || step == 3000) {
      for (int r = 0; r < n; ++r)
        for (size_t i = 0; i < def.links.size(); ++i)
          poses[r * def.links.size() + i] = world.bodyPose(ragdolls[r].bodies[i]);
      m.sample(def, poses, n, step, dt, 3000);
    }
  }
  const double loop_wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - loop0).count();
  const long bodies = long(n) * long(def.links.size()) + long(sc.boxes.size());
  // Scene p: did every ragdoll end up inside the pit (pelvis within the walls' inner faces),
  // and how high is the pile at the end?
  std::string extra;  // scene p's fields and the what-if options, at the end of the line
  if (!sc.walls.empty()) {
    int outside = 0;
    double top = 0.0;
    for (const Ragdoll& r : ragdolls) {
      const Vec3 p = world.bodyPose(r.bodies[0]).p;
      if (std::abs(p.x()) > 1.5 || std::abs(p.y()) > 1.5) ++outside;
      top = std::max(top, p.z());
    }
    char buf[96];
    std::snprintf(buf, sizeof buf, " pit_outside_end=%d pelvis_z_end_max=%.3f", outside, top);
    extra = buf;
  }
  if (joint_damping > 0.0 || joint_friction > 0.0) {
    char buf[96];
    std::snprintf(buf, sizeof buf, " joint_damping=%g joint_friction=%g", joint_damping,
                  joint_friction);
    extra += buf;
  }
  if (track) {
    char buf[64];
    std::snprintf(buf, sizeof buf, " track=1 reports=%d reported_points=%zu", reports ? 1 : 0,
                  reported_points);
    extra += buf;
  }
  if (profile) {
    char buf[64];
    for (size_t k = 0; k < kProfileFields.size(); ++k) {
      std::snprintf(buf, sizeof buf, " profile_%s_us=%.2f", kProfileNames[k],
                    phases.*kProfileFields[k] / steps);
      extra += buf;
    }
    // The wide solver's batches per step and how full their lanes were (IslandCounters).
    const auto fill = [](long rows, long lanes) { return lanes > 0 ? double(rows) / lanes : 0.0; };
    std::snprintf(buf, sizeof buf, " lane_batches=%.2f", double(lanes.lane_batches) / steps);
    extra += buf;
    std::snprintf(buf, sizeof buf, " contact_lane_fill=%.3f joint_lane_fill=%.3f",
                  fill(lanes.contact_lane_rows, lanes.contact_lanes),
                  fill(lanes.joint_lane_rows, lanes.joint_lanes));
    extra += buf;
  }
  if (hash) {
    char buf[48];
    std::snprintf(buf, sizeof buf, " state_hash=%016llx", (unsigned long long)state_hash);
    extra += buf;
  }
  const double sps = steps / wall;
  std::printf(
      "engine=ragdoll_sim scenario=%c ragdolls=%d bodies=%ld steps=%d wall_s=%.4f steps_per_s=%.1f "
      "body_steps_per_s=%.0f us_per_body_step=%.3f max_anchor_err_m=%.3g max_ground_pen_m=%.4f "
      "max_limit_viol_rad=%.3g pelvis_z_3s_mean=%.4f pelvis_z_3s_min=%.4f pelvis_z_3s_max=%.4f "
      "ground_pen_3s_m=%.4f anchor_err_3s_m=%.3g vmax_3s=%.3g worst_limit=%s@%d nan=%d "
      "loop_wall_s=%.3f substeps=%d joint_hertz=%g contact_hertz=%g sleep=%d threads=%d rolling=%g yaw=%g max_contacts=%zu "
      "us_per_step_first_1s=%.1f us_per_step_last_1s=%.1f awake_bodies_end=%d "
      "awake_body_steps=%ld resting_body_steps=%ld worst_pen=%s@%d worst_anchor=%s@%d%s\n",
      sc.id, n, bodies, steps, wall, sps, sps * bodies, 1e6 * wall / (steps * double(bodies)),
      m.max_anchor, m.max_pen, m.max_limit, m.pel_mean, m.pel_min, m.pel_max, m.pen3, m.anchor3,
      m.vmax3, m.worst_joint.c_str(), m.worst_step, m.nan ? 1 : 0, loop_wall, wd.solver.substeps,
      wd.solver.joint_hertz, wd.solver.contact_hertz, wd.sleep.enabled ? 1 : 0, wd.threads, rolling, yaw, world.contacts().size(),
      1e6 * wall_first / window, 1e6 * wall_last / window, world.awakeBodyCount(),
      awake_body_steps, resting_body_steps, m.pen_link.c_str(), m.pen_step, m.anchor_joint.c_str(), m.anchor_step, extra.c_str());
  return 0;
}
