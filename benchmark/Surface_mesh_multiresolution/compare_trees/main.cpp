// SPDX-License-Identifier: GPL-3.0-or-later
// compare_trees.sh's driver: loads the mesh once per tree, then alternates the two trees'
// decompositions and reconstructions (A B, then B A, ...) in one process and prints, for each
// step, the best time of each tree, the ratio of the bests and the median of the pairs' ratios,
// and whether the pyramids are the same bit for bit (the reconstructions: exact on both).
#include <tbb/global_control.h>

#include <algorithm>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <vector>

extern "C" bool a_load(const char*);
extern "C" double a_decompose(std::uint64_t*);
extern "C" double a_reconstruct(bool*);
extern "C" bool b_load(const char*);
extern "C" double b_decompose(std::uint64_t*);
extern "C" double b_reconstruct(bool*);

int main(int argc, char** argv)
{
  if(argc < 4)
  {
    std::fprintf(stderr, "usage: %s FILE THREADS ROUNDS\n", argv[0]);
    return 1;
  }
  const int threads = std::atoi(argv[2]), rounds = (std::max)(1, std::atoi(argv[3]));
  tbb::global_control limit(tbb::global_control::max_allowed_parallelism, std::size_t((std::max)(1, threads)));
  if(!a_load(argv[1]) || !b_load(argv[1]))
  {
    std::fprintf(stderr, "cannot read %s\n", argv[1]);
    return 1;
  }
  std::uint64_t hash_a = 0, hash_b = 0;
  bool exact_a = false, exact_b = false;
  a_decompose(&hash_a);                                     // first runs: the pyramids compared, not timed
  a_reconstruct(&exact_a);
  b_decompose(&hash_b);
  b_reconstruct(&exact_b);
  // decompositions and reconstructions, each alternating A B, then B A, ...
  std::vector<double> times[2][2], ratios[2];
  for(int r = 0; r < rounds; ++r)
  {
    double t[2][2];                                         // [step][tree]
    for(int side = 0; side < 2; ++side)
    {
      const int tree = (r % 2 == 0) ? side : 1 - side;
      t[0][tree] = tree == 0 ? a_decompose(nullptr) : b_decompose(nullptr);
      t[1][tree] = tree == 0 ? a_reconstruct(nullptr) : b_reconstruct(nullptr);
    }
    for(int step = 0; step < 2; ++step)
    {
      times[step][0].push_back(t[step][0]);
      times[step][1].push_back(t[step][1]);
      ratios[step].push_back(t[step][1] / t[step][0]);
    }
  }
  std::printf("| step | threads | pairs | A best (s) | B best (s) | B / A, bests | B / A, median of the pairs | same result |\n");
  std::printf("|---|---:|---:|---:|---:|---:|---:|---|\n");
  const char* names[2] = {"decompose", "reconstruct"};
  for(int step = 0; step < 2; ++step)
  {
    std::vector<double>& q = ratios[step];
    std::sort(q.begin(), q.end());
    const double median = rounds % 2 ? q[rounds / 2] : 0.5 * (q[rounds / 2 - 1] + q[rounds / 2]);
    const double best_a = *std::min_element(times[step][0].begin(), times[step][0].end());
    const double best_b = *std::min_element(times[step][1].begin(), times[step][1].end());
    const bool same = step == 0 ? hash_a == hash_b : (exact_a && exact_b);
    std::printf("| %s | %d | %d | %.3f | %.3f | %.3f | %.3f | %s |\n", names[step], threads, rounds, best_a, best_b,
                best_b / best_a, median, same ? "yes" : "NO");
  }
  return 0;
}
