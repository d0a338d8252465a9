// Injury metrics: HicMeter against closed forms (a constant pulse gives T a^2.5, a longer one
// window a^2.5) and against a brute-force evaluation of the definition (a half-sine pulse);
// the Scene's injury records: a head dropped on the ground, records reset, refused names,
// guessed heads, removal and reset.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <functional>
#include <string>
#include <vector>

#include "object_models.hpp"
#include "ragdoll_sim/injury.hpp"
#include "ragdoll_sim/scene.hpp"
#include "scene_recorder.hpp"

using namespace ragdoll_sim;

namespace {

constexpr double kPi = 3.14159265358979323846;

// accel(ta, tb): mean acceleration (g) over [ta, tb]; `length` s in samples of dt.
void feed(HicMeter& m, double length, double dt, const std::function<double(double, double)>& accel) {
  const int n = static_cast<int>(std::lround(length / dt));
  for (int i = 0; i < n; ++i) m.add(accel(i * dt, (i + 1) * dt), dt);
}

// A pulse of `a` g from t0 for T s, zero around it.
std::function<double(double, double)> squarePulse(double a, double t0, double T) {
  return [=](double ta, double tb) {
    const double overlap = std::max(0.0, std::min(tb, t0 + T) - std::max(ta, t0));
    return a * overlap / (tb - ta);
  };
}

// A half-sine pulse of peak `a` g from t0 for T s: the exact mean over each interval.
std::function<double(double, double)> halfSine(double a, double t0, double T) {
  return [=](double ta, double tb) {
    const double lo = std::clamp(ta - t0, 0.0, T), hi = std::clamp(tb - t0, 0.0, T);
    return a * T / kPi * (std::cos(kPi * lo / T) - std::cos(kPi * hi / T)) / (tb - ta);
  };
}

// The definition by brute force: every pair of sample boundaries at most `window` apart.
double bruteHic(const std::vector<double>& a, double dt, double window) {
  std::vector<double> integral(a.size() + 1, 0.0);
  for (size_t i = 0; i < a.size(); ++i) integral[i + 1] = integral[i] + a[i] * dt;
  const size_t span = static_cast<size_t>(std::lround(window / dt));
  double best = 0.0;
  for (size_t i = 0; i < integral.size(); ++i)
    for (size_t j = i + 1; j < integral.size() && j - i <= span; ++j) {
      const double T = (j - i) * dt, mean = (integral[j] - integral[i]) / T;
      best = std::max(best, T * std::pow(mean, 2.5));
    }
  return best;
}

}  // namespace

TEST(HicMeter, ConstantPulseGivesDurationTimesAccelerationToThe2Point5) {
  const double a = 60.0, dt = 0.25e-3, t0 = 0.005;
  for (const double T : {0.003, 0.010, 0.015, 0.030, 0.050}) {
    HicMeter h15(0.015), h36(0.036);
    for (HicMeter* m : {&h15, &h36}) feed(*m, t0 + T + 0.04, dt, squarePulse(a, t0, T));
    const double expect15 = std::min(T, 0.015) * std::pow(a, 2.5);
    const double expect36 = std::min(T, 0.036) * std::pow(a, 2.5);
    EXPECT_NEAR(h15.hic(), expect15, 0.005 * expect15) << "T " << T;
    EXPECT_NEAR(h36.hic(), expect36, 0.005 * expect36) << "T " << T;
    if (T <= 0.015) {  // the pulse itself is the window
      EXPECT_NEAR(h15.t1(), t0, 1e-9);
      EXPECT_NEAR(h15.t2(), t0 + T, 1e-9);
    } else {  // some window of the limit's length inside it
      EXPECT_NEAR(h15.t2() - h15.t1(), 0.015, 1e-9);
      EXPECT_GE(h15.t1(), t0 - 1e-9);
      EXPECT_LE(h15.t2(), t0 + T + 1e-9);
    }
  }
}

TEST(HicMeter, HalfSineMatchesBruteForceAtTenTimesFinerSampling) {
  const double a = 80.0, T = 0.010, t0 = 0.004, length = 0.030;
  for (const double window : {0.015, 0.036}) {
    HicMeter m(window);
    feed(m, length, 0.25e-3, halfSine(a, t0, T));
    const double fine_dt = 0.025e-3;
    std::vector<double> fine;
    const auto pulse = halfSine(a, t0, T);
    for (int i = 0; i < static_cast<int>(std::lround(length / fine_dt)); ++i)
      fine.push_back(pulse(i * fine_dt, (i + 1) * fine_dt));
    const double brute = bruteHic(fine, fine_dt, window);
    EXPECT_NEAR(m.hic(), brute, 0.005 * brute) << "window " << window;
    // The window found lies over the pulse's middle.
    EXPECT_GT(m.t1(), t0);
    EXPECT_LT(m.t2(), t0 + T);
    EXPECT_NEAR(0.5 * (m.t1() + m.t2()), t0 + 0.5 * T, 0.25e-3);
    std::printf("[ hic      ] half-sine %g g %g ms, window %g ms: HIC %.1f (brute force %.1f), "
                "%.2f-%.2f ms\n", a, T * 1e3, window * 1e3, m.hic(), brute, m.t1() * 1e3,
                m.t2() * 1e3);
  }
}

TEST(HicMeter, ResetAndBadSamples) {
  HicMeter m;
  EXPECT_EQ(m.window(), 0.015);
  feed(m, 0.02, 1e-3, squarePulse(50.0, 0.0, 0.005));
  EXPECT_GT(m.hic(), 0.0);
  m.reset();
  EXPECT_EQ(m.hic(), 0.0);
  m.add(NAN, 1e-3);         // counts as 0
  m.add(10.0, 0.0);         // no interval: ignored
  m.add(10.0, NAN);
  m.add(-5.0, 1e-3);        // counts as 0
  EXPECT_EQ(m.hic(), 0.0);
  m.add(10.0, 1e-3);
  EXPECT_NEAR(m.hic(), 1e-3 * std::pow(10.0, 2.5), 1e-9);
  EXPECT_NEAR(m.t1(), 2e-3, 1e-12);
}

// ------------------------------------------------------------------------------------------
// Scene records

namespace {

// A ragdoll of one link "head": a 4.5 kg ball of radius 0.1 m (a rigid head), and a second
// link hung below it so that it has a neck.
RagdollDef headModel(const std::string& head = "head") {
  RagdollDef def;
  def.name = "headball";
  LinkDef h;
  h.name = head;
  h.mass = 4.5;
  h.inertia = Mat3::Identity() * (0.4 * 4.5 * 0.01);
  h.shapes.push_back({Geometry::sphere(0.1), Transform(), Material()});
  def.links.push_back(h);
  return def;
}

SpawnDef drop(const RagdollDef& def, double height, const std::string& name = "r") {
  SpawnDef s;
  s.name = name;
  s.def = def;
  s.pose = Transform(Vec3(0, 0, 0.1 + height), Quat::Identity());
  return s;
}

// Steps until an injury report comes (at most `seconds`); the first report, reason "" if none.
InjuryReport stepUntilReport(Scene& scene, double seconds) {
  for (int i = 0; i < static_cast<int>(seconds / scene.dt()); ++i) {
    scene.step();
    if (!scene.injuryReports().empty()) return scene.injuryReports().front();
  }
  return InjuryReport();
}

}  // namespace

// Dropped from 0.5 m: the impact at t = sqrt(2 h / g) gives a finite peak well above 1 g,
// HIC windows around it, and the report comes once the ball has been still for rest_time.
TEST(SceneInjury, DroppedHeadIsReportedAtRest) {
  Scene scene{SceneDef()};
  std::string e;
  ASSERT_EQ(scene.addRagdoll(drop(headModel(), 0.5), &e), SpawnResult::Added) << e;
  ASSERT_TRUE(scene.start(&e)) << e;
  EXPECT_EQ(scene.headLink(0), "head");
  EXPECT_EQ(scene.neckJoint(0), "");
  const InjuryReport r = stepUntilReport(scene, 3.0);
  ASSERT_EQ(r.reason, "rest");
  const double impact = std::sqrt(2 * 0.5 / kStandardGravity);
  EXPECT_EQ(r.ragdoll, "r");
  EXPECT_EQ(r.head_link, "head");
  // The fall starts in the step where the ball passes fall_speed.
  EXPECT_NEAR(r.start_time, InjuryDef().fall_speed / kStandardGravity, 1.5e-3);
  EXPECT_TRUE(std::isfinite(r.peak_g));
  EXPECT_GT(r.peak_g, 20.0);
  EXPECT_NEAR(r.peak_time, impact, 0.01);
  EXPECT_GE(r.end_time, r.peak_time + InjuryDef().rest_time);
  EXPECT_LT(r.end_time, r.peak_time + InjuryDef().rest_time + 0.3);
  EXPECT_GT(r.hic15, 0.0);
  EXPECT_GE(r.hic36, r.hic15);
  EXPECT_LE(r.hic15_t1, r.peak_time + 1e-9);  // the meter sums substeps from the start
  EXPECT_GE(r.hic15_t2, r.peak_time - 1e-9);
  EXPECT_LE(r.hic15_t2 - r.hic15_t1, 0.015 + 1e-9);
  EXPECT_LE(r.hic36_t2 - r.hic36_t1, 0.036 + 1e-9);
  EXPECT_GT(r.peak_angular_acceleration, -1.0);
  std::printf("[ injury   ] 0.5 m drop, rigid ground: peak %.0f g at %.4f s, HIC15 %.1f "
              "(%.4f-%.4f s), HIC36 %.1f, report at %.3f s\n", r.peak_g, r.peak_time, r.hic15,
              r.hic15_t1, r.hic15_t2, r.hic36, r.end_time);
  // The ball rests on the ground (1 g) at the end of the fall; no fall since: an empty record.
  EXPECT_GT(r.peak_g, 0.0);
  for (int i = 0; i < 50; ++i) scene.step();
  const InjuryReport now = scene.injury(0);
  EXPECT_EQ(now.reason, "");
  EXPECT_NEAR(now.start_time, r.end_time, 1e-9);
  EXPECT_EQ(now.peak_g, 0.0);
  EXPECT_EQ(now.hic15, 0.0);
}

// The same drop on a padded mat (Material::contact_hertz 30 Hz): the head is stopped over a
// few ms instead of one substep, so its peak g and HIC are far lower.
TEST(SceneInjury, SofterGroundGivesLowerPeak) {
  const auto dropOn = [](double hertz) {
    SceneDef d;
    d.ground_surface.contact_hertz = hertz;
    Scene scene{d};
    std::string e;
    EXPECT_EQ(scene.addRagdoll(drop(headModel(), 0.5), &e), SpawnResult::Added) << e;
    EXPECT_TRUE(scene.start(&e)) << e;
    return stepUntilReport(scene, 3.0);
  };
  const InjuryReport rigid = dropOn(0.0), soft = dropOn(30.0);
  ASSERT_EQ(rigid.reason, "rest");
  ASSERT_EQ(soft.reason, "rest");
  EXPECT_LT(soft.peak_g, 0.5 * rigid.peak_g);
  EXPECT_GT(soft.peak_g, 2.0);
  EXPECT_LT(soft.hic15, rigid.hic15);
  std::printf("[ injury   ] 0.5 m drop: rigid %.0f g HIC15 %.0f; mat 30 Hz %.1f g HIC15 %.1f "
              "(%.4f-%.4f s)\n", rigid.peak_g, rigid.hic15, soft.peak_g, soft.hic15,
              soft.hic15_t1, soft.hic15_t2);
}

TEST(SceneInjury, ResetInjuryReturnsTheRecordAndStartsAnew) {
  Scene scene{SceneDef()};
  std::string e;
  ASSERT_EQ(scene.addRagdoll(drop(headModel(), 0.3), &e), SpawnResult::Added) << e;
  ASSERT_TRUE(scene.start(&e)) << e;
  for (int i = 0; i < 400; ++i) scene.step();  // past the impact, not yet at rest
  const InjuryReport r = scene.resetInjury(0);
  EXPECT_EQ(r.reason, "reset");
  EXPECT_GT(r.peak_g, 10.0);
  EXPECT_NEAR(r.end_time, 0.4, 1e-9);
  const InjuryReport fresh = scene.injury(0);
  EXPECT_EQ(fresh.peak_g, 0.0);
  EXPECT_NEAR(fresh.start_time, 0.4, 1e-9);
  // No fall under way any more: the ball comes to rest without another report.
  for (int i = 0; i < 1500; ++i) {
    scene.step();
    EXPECT_TRUE(scene.injuryReports().empty());
  }
}

TEST(SceneInjury, UnknownNamesAreRefusedNamingThem) {
  Scene scene{SceneDef()};
  std::string e;
  ASSERT_EQ(scene.addRagdoll(drop(test::bundledRagdoll(), 0.2), &e), SpawnResult::Added) << e;
  ASSERT_TRUE(scene.start(&e)) << e;
  EXPECT_EQ(scene.headLink(0), "head");
  EXPECT_EQ(scene.neckJoint(0), "neck_y+neck_x+neck_z");
  InjuryDef d;
  d.head_link = "noggin";
  EXPECT_FALSE(scene.setInjury(0, d, &e));
  EXPECT_NE(e.find("'noggin'"), std::string::npos) << e;
  EXPECT_EQ(scene.headLink(0), "head");  // unchanged
  d = InjuryDef();
  d.neck_joint = "nape";
  e.clear();
  EXPECT_FALSE(scene.setInjury(0, d, &e));
  EXPECT_NE(e.find("'nape'"), std::string::npos) << e;
  // A URDF joint of the ball names it; another head link.
  d.neck_joint = "neck_x";
  ASSERT_TRUE(scene.setInjury(0, d, &e)) << e;
  EXPECT_EQ(scene.neckJoint(0), "neck_y+neck_x+neck_z");
  d = InjuryDef();
  d.head_link = "torso";
  ASSERT_TRUE(scene.setInjury(0, d, &e)) << e;
  EXPECT_EQ(scene.headLink(0), "torso");
  EXPECT_EQ(scene.neckJoint(0), "waist_y+waist_x+waist_z");
  // Off: nothing tracked.
  d.enabled = false;
  ASSERT_TRUE(scene.setInjury(0, d, &e)) << e;
  EXPECT_EQ(scene.headLink(0), "");
  scene.step();
  SubstepVelocities s;
  for (const BodyId b : scene.bodies(0).bodies) EXPECT_FALSE(scene.world().substepVelocities(b, &s));
}

// Other models: a head guessed by name (INFO naming it), or none (INFO, no record).
TEST(SceneInjury, HeadGuessedByNameOrNone) {
  test::Recorder rec;
  Scene scene{SceneDef(), &rec};
  std::string e;
  ASSERT_EQ(scene.addRagdoll(drop(headModel("Robot_Head_Link"), 1.0, "a"), &e),
            SpawnResult::Added);
  ASSERT_EQ(scene.addRagdoll(drop(headModel("ball"), 1.0, "b"), &e), SpawnResult::Added);
  SpawnDef crate = test::boxObject("crate", Vec3(0.1, 0.1, 0.1), 1.0, Vec3(2, 0, 1));
  ASSERT_EQ(scene.addObject(crate, &e), SpawnResult::Added) << e;
  ASSERT_TRUE(scene.start(&e)) << e;
  EXPECT_EQ(scene.headLink(0), "Robot_Head_Link");
  EXPECT_EQ(scene.headLink(1), "");
  EXPECT_EQ(scene.headLink(2), "");  // an object
  int guessed = 0, none = 0;
  for (const SceneMessage& m : rec.messages) {
    guessed += m.level == SceneMessage::Level::Info && m.text.find("'Robot_Head_Link'") != std::string::npos;
    none += m.level == SceneMessage::Level::Info && m.text.find("'b': no link named like a head") != std::string::npos;
  }
  EXPECT_EQ(guessed, 1);
  EXPECT_EQ(none, 1);
  EXPECT_FALSE(scene.setInjury(2, InjuryDef(), &e));
  EXPECT_NE(e.find("object"), std::string::npos) << e;
}

// Removal during a fall reports it; a reset rebuilds the World and the records start afresh
// with the head tracked in the new World.
TEST(SceneInjury, RemovalReportsAFallAndResetRetracks) {
  Scene scene{SceneDef()};
  std::string e;
  ASSERT_EQ(scene.addRagdoll(drop(headModel(), 0.5, "a"), &e), SpawnResult::Added);
  ASSERT_EQ(scene.addRagdoll(drop(headModel(), 0.5, "b"), &e), SpawnResult::Added);
  ASSERT_TRUE(scene.start(&e)) << e;
  for (int i = 0; i < 200; ++i) scene.step();  // falling
  ASSERT_TRUE(scene.removeRagdoll("b", &e)) << e;
  ASSERT_EQ(scene.injuryReports().size(), 1u);
  EXPECT_EQ(scene.injuryReports()[0].ragdoll, "b");
  EXPECT_EQ(scene.injuryReports()[0].reason, "removed");
  scene.step();
  ASSERT_EQ(scene.injuryReports().size(), 1u);  // kept for the step after the removal
  scene.step();
  EXPECT_TRUE(scene.injuryReports().empty());
  ASSERT_TRUE(scene.reset(&e)) << e;
  EXPECT_EQ(scene.injury(0).peak_g, 0.0);
  const double reset_at = scene.time();
  const InjuryReport r = stepUntilReport(scene, 3.0);
  ASSERT_EQ(r.reason, "rest");
  EXPECT_GT(r.peak_g, 20.0);
  EXPECT_NEAR(r.peak_time - reset_at, std::sqrt(2 * 0.5 / kStandardGravity), 0.01);
}

// The bundled ragdoll collapsing from standing: the neck (World::jointWrench) holds at least the
// head's weight at some point, and the fall ends at rest within the run.
TEST(SceneInjury, BundledRagdollNeckLoads) {
  Scene scene{SceneDef()};
  std::string e;
  const RagdollDef def = test::bundledRagdoll();
  SpawnDef s = drop(def, 0.0);
  s.pose.p.z() = 1.05;  // its lowest point 5 cm above the ground
  ASSERT_EQ(scene.addRagdoll(s, &e), SpawnResult::Added) << e;
  ASSERT_TRUE(scene.start(&e)) << e;
  const InjuryReport r = stepUntilReport(scene, 4.0);
  ASSERT_EQ(r.reason, "rest");
  EXPECT_EQ(r.neck_joint, "neck_y+neck_x+neck_z");
  const double head_weight = def.links[static_cast<size_t>(def.findLink("head"))].mass * kStandardGravity;
  EXPECT_GT(r.peak_neck_force, head_weight);
  EXPECT_TRUE(std::isfinite(r.peak_neck_force));
  EXPECT_GT(r.peak_neck_torque, 0.0);
  EXPECT_TRUE(std::isfinite(r.peak_neck_torque));
  EXPECT_GT(r.peak_g, 1.0);
  std::printf("[ injury   ] bundled ragdoll from standing: peak %.0f g at %.3f s, HIC15 %.0f, "
              "neck %.0f N / %.1f N m, fall %.3f-%.3f s\n", r.peak_g, r.peak_time, r.hic15,
              r.peak_neck_force, r.peak_neck_torque, r.start_time, r.end_time);
}
