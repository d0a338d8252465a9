// shape_boxes_kernel.hpp against the Eigen code it replaces (World::Impl::computeBox: the shape's
// frame, computeAabb, the growth): one shape (double), two (Double2 lanes) and four (AVX lanes,
// where the CPU has AVX2) must give its bits for every kind of shape.
#include <gtest/gtest.h>

#include <cstring>
#include <random>
#include <vector>

#include "lane_width.hpp"
#include "narrowphase.hpp"
#include "ragdoll_sim/shape.hpp"
#include "shape_boxes_kernel.hpp"

namespace ragdoll_sim {
namespace {

using shape_boxes::ShapeBoxJob;

struct Case {
  Geometry g;
  Vec3 x, v, com;
  Quat q;
  Transform local;
  Transform frame;  // out
  Aabb box;         // out
};

// computeBox's Eigen code.
void reference(const Case& c, double spec, double dt, Transform& frame, Aabb& box) {
  frame = {c.q * (c.local.p - c.com), c.q * c.local.q};
  box = computeAabb(c.g, {c.x + frame.p, frame.q});
  const Vec3 grow = Vec3::Constant(spec) + (c.v * dt).cwiseAbs();
  box.lo -= grow;
  box.hi += grow;
}

Quat randomQuat(std::mt19937& rng, int k) {
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  switch (k % 5) {  // axis-aligned ones too: a cylinder's 1 - w^2 is then 0 or -0
    case 0: return Quat::Identity();
    case 1: return Quat(0.0, -0.0, 1.0, 0.0);
    case 2: return Quat(std::sqrt(0.5), 0.0, std::sqrt(0.5), 0.0);
    default: return Quat(u(rng), u(rng), u(rng), u(rng)).normalized();
  }
}

std::vector<Case> makeCases(ShapeType type, int n, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(-1.0, 1.0), pos(0.01, 1.0);
  std::vector<Case> cases(n);
  for (int k = 0; k < n; ++k) {
    Case& c = cases[k];
    switch (type) {
      case ShapeType::Sphere: c.g = Geometry::sphere(pos(rng)); break;
      case ShapeType::Capsule: c.g = Geometry::capsule(pos(rng), pos(rng)); break;
      case ShapeType::Box: c.g = Geometry::box(Vec3(pos(rng), pos(rng), pos(rng))); break;
      default: c.g = Geometry::cylinder(pos(rng), pos(rng)); break;
    }
    c.x = 100.0 * Vec3(u(rng), u(rng), u(rng));
    c.v = 10.0 * Vec3(u(rng), u(rng), u(rng));
    if (k % 7 == 0) c.v = Vec3(0.0, -0.0, 0.0);
    c.com = 0.1 * Vec3(u(rng), u(rng), u(rng));
    c.q = randomQuat(rng, k);
    c.local = {0.2 * Vec3(u(rng), u(rng), u(rng)), randomQuat(rng, k / 5)};
  }
  return cases;
}

// The cases through the kernel, `width` shapes at a time (4: the AVX kernel).
void kernelBoxes(ShapeType type, int width, double spec, double dt, std::vector<Case>& cases) {
  const int kind = int(type);
  std::vector<ShapeBoxJob> jobs;
  for (Case& c : cases)
    jobs.push_back({c.x.data(), c.q.coeffs().data(), c.v.data(), c.com.data(),
                    c.local.p.data(), c.local.q.coeffs().data(),
                    type == ShapeType::Box ? c.g.half_extents.data() : &c.g.radius,
                    c.frame.p.data(), c.frame.q.coeffs().data(), c.box.lo.data(), c.box.hi.data()});
  const int n = int(jobs.size());
  using shape_boxes::shapeBoxesOf;
  if (width == 4) shape_boxes_w4::shapeBoxes(kind, jobs.data(), n, spec, dt);
  else if (width == 2) shapeBoxesOf<double_lanes::Double2>(kind, jobs.data(), n, spec, dt);
  else shapeBoxesOf<double>(kind, jobs.data(), n, spec, dt);
}

bool sameBits(const double* a, const double* b, int n) {
  return std::memcmp(a, b, n * sizeof(double)) == 0;
}

TEST(ShapeBoxes, LanesGiveTheBitsOfTheEigenCode) {
  std::vector<int> widths = {1, 2};
  if (cpuHasAvx2()) widths.push_back(4);
  const double spec = 0.02, dt = 1.0 / 600.0;
  for (const ShapeType type :
       {ShapeType::Sphere, ShapeType::Capsule, ShapeType::Box, ShapeType::Cylinder}) {
    for (const int width : widths) {
      std::vector<Case> cases = makeCases(type, 40, 7 + int(type));
      kernelBoxes(type, width, spec, dt, cases);
      for (size_t k = 0; k < cases.size(); ++k) {
        const Case& c = cases[k];
        Transform frame;
        Aabb box;
        reference(c, spec, dt, frame, box);
        const char* name = shapeTypeName(type);
        EXPECT_TRUE(sameBits(frame.p.data(), c.frame.p.data(), 3)) << name << " w" << width << " #" << k;
        EXPECT_TRUE(sameBits(frame.q.coeffs().data(), c.frame.q.coeffs().data(), 4))
            << name << " w" << width << " #" << k;
        EXPECT_TRUE(sameBits(box.lo.data(), c.box.lo.data(), 3)) << name << " w" << width << " #" << k;
        EXPECT_TRUE(sameBits(box.hi.data(), c.box.hi.data(), 3)) << name << " w" << width << " #" << k;
      }
    }
  }
}

}  // namespace
}  // namespace ragdoll_sim
