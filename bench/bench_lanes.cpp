// Rows per second of the contact normal row: the double row of contact_solver.cpp (a copy,
// test/core/normal_row_double.hpp) against the float-lane kernel at 4 and 8 lanes, one thread.
//   bench_lanes [rows=10000] [bodies=2500] [sweeps=200]
// Each sweep solves every row once (the rows of a block share no body, blocks do), alternating
// the biased and the relax sweep; the best of 5 rounds is printed.
#include <chrono>
#include <cstdio>
#include <cstdlib>

#include "lane_rows.hpp"
#include "lane_width.hpp"

using namespace ragdoll_sim;
using namespace ragdoll_sim::lane_test;

namespace {

template <class Sweep>
double bestRowsPerSecond(int rows, int sweeps, Sweep sweep) {
  double best = 0.0;
  for (int round = 0; round < 5; ++round) {
    const auto t0 = std::chrono::steady_clock::now();
    for (int s = 0; s < sweeps; ++s) sweep(s % 2 == 0);
    const double dt = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    best = std::max(best, double(rows) * sweeps / dt);
  }
  return best;
}

}  // namespace

int main(int argc, char** argv) {
  const int rows = argc > 1 ? std::atoi(argv[1]) : 10000;
  const int body_count = argc > 2 ? std::atoi(argv[2]) : 2500;
  const int sweeps = argc > 3 ? std::atoi(argv[3]) : 200;
  if (rows < 1 || body_count < 2 * kRowBlock || sweeps < 1) {
    std::fprintf(stderr, "bench_lanes: rows >= 1, bodies >= %d, sweeps >= 1\n", 2 * kRowBlock);
    return 1;
  }
  const RowSet set = makeRows(rows, body_count, true, 1);

  RowSet d = set;
  const double rate_d = bestRowsPerSecond(rows, sweeps, [&](bool bias) {
    d.params_d.use_bias = bias;
    solveNormalRowsD(d.rows, d.bodies, d.params_d);
  });
  std::printf("rows %d bodies %d sweeps %d\n", rows, body_count, sweeps);
  std::printf("double row  %8.1f Mrows/s\n", rate_d * 1e-6);

  double rate_4 = 0.0;
  for (int width : {4, 8}) {
    if (width == 8 && !cpuHasAvx2()) {
      std::printf("8 lanes     (no AVX2)\n");
      continue;
    }
    std::vector<NormalRowBlock> blocks = set.blocks;
    BodyArraysF f(set.bodies);
    NormalRowParams p = set.params;
    const double rate = bestRowsPerSecond(rows, sweeps, [&](bool bias) {
      p.use_bias = bias;
      if (width == 8) kernel_w8::solveNormalRows(blocks.data(), int(blocks.size()), f.view(), p);
      else kernel_w4::solveNormalRows(blocks.data(), int(blocks.size()), f.view(), p);
    });
    if (width == 4) rate_4 = rate;
    std::printf("%d lanes     %8.1f Mrows/s  %.2fx double  (bodies as fields)\n", width,
                rate * 1e-6, rate / rate_d);
    if (width == 8) std::printf("8 / 4 lanes %8.2fx\n", rate / rate_4);
    std::vector<BodyVelocityF> records = bodyRecordsF(set.bodies);
    std::vector<NormalRowBlock> blocks2 = set.blocks;
    const double rate_aos = bestRowsPerSecond(rows, sweeps, [&](bool bias) {
      p.use_bias = bias;
      if (width == 8)
        kernel_w8::solveNormalRowsAos(blocks2.data(), int(blocks2.size()), records.data(), p);
      else kernel_w4::solveNormalRowsAos(blocks2.data(), int(blocks2.size()), records.data(), p);
    });
    std::printf("%d lanes     %8.1f Mrows/s  %.2fx double  (bodies as 8-float records)\n", width,
                rate_aos * 1e-6, rate_aos / rate_d);
  }
  return 0;
}
