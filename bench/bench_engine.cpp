// SPDX-License-Identifier: GPL-3.0-or-later
// SPDX-FileCopyrightText: 2026 The dda maintainers
// Engine step benchmark in C++ (the benchmark table itself is scripts/bench/run.sh).
//
//   ./build/bench/bench_engine                       # wall(10,20,40); 1 and 2 threads
//   ./build/bench/bench_engine --scenes wall10,wall40 --threads 2 --pre bj,mg
//   ./build/bench/bench_engine --scenes wall100 --threads 2 --steps 3   # minutes per step
//   ./build/bench/bench_engine --budget 20 --steps 40 --csv out.csv
//   ./build/bench/bench_engine --solver-only        # the linear solver alone, cold solves
//   ./build/bench/bench_engine --scenes wall40 --threads 2 --pre pcg,chol --gg 1   # dynamic walls
//
// Scenes: wall(N), the quasi-static brick wall of scripts/bench/scenes.lua
// (tests/scenes.hpp: test::brick_wall; 211 / 821 / 3,241 / 20,101 blocks for
// N = 10 / 20 / 40 / 100). The wave problems (blast, the rock bar) are
// benchmarked from Lua: scripts/bench/bench.lua.
//
// --pre names the solvers: auto (the automatic choice of solver and
// preconditioner), pcg (PCG, its automatic preconditioner), bj or mg (PCG
// with block-Jacobi or multigrid), chol (the CHOLMOD factor). --gg sets the
// walls' dynamic parameter (0: quasi-static, as scenes.lua; 1: dynamic).
//
// Each (scene, threads, solver) runs in a child process, so that its
// peak RSS is its own. A few warm-up steps are run first (not timed), then
// steps are timed until --steps are done or --budget seconds have passed.
// Per run: blocks, contacts, ms/step, block-steps/s, open-close and CG
// iterations per step, step cuts, the share of each stage of the step, and
// peak RSS. Then, for the walls, the linear solver alone: the last system
// solved cold with block-Jacobi and with multigrid PCG (iterations, ms, the
// multigrid's level sizes). Figures only; nothing is asserted.
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <ctime>
#include <string>
#include <vector>

#include "scenes.hpp"  // tests/: test::brick_wall
#include "solver/cholmod_factor.hpp"
#include "solver/multigrid.hpp"
#include "solver/pcg.hpp"
#include "world/world.hpp"

using namespace dda;

namespace {

std::string display_name(const std::string& scene) {
  if (scene.rfind("wall", 0) == 0) return "wall(" + scene.substr(4) + ")";
  return scene;
}

struct Result {
  int blocks = 0, contacts = 0, steps = 0, cuts = 0;
  double ms_per_step = 0, oc_per_step = 0, cg_per_step = 0, factorisations_per_step = 0;
  char solver[16] = {};                                                          // the last step's
  double detect = 0, assemble = 0, solve = 0, check = 0, update = 0, total = 0;  // seconds, summed
  double peak_rss_mb = 0;
  bool failed = false;
  char error[160] = {};
};

void set_solver(const std::string& s, SolverSettings& settings) {
  settings.kind = s == "auto" ? SolverKind::Auto : s == "chol" ? SolverKind::Cholmod : SolverKind::Pcg;
  settings.pcg.preconditioner = s == "bj"   ? Preconditioning::BlockJacobi
                                : s == "mg" ? Preconditioning::Multigrid
                                            : Preconditioning::Auto;
}

double g_gg = 0;     // --gg
int g_refactor = 0;  // --refactor: CholmodSettings::refactor_iterations (0: its default)

Result run(const std::string& scene, int threads, const std::string& pre, int warmup, int max_steps, double budget) {
  Result r;
  World w = test::brick_wall(std::atoi(scene.c_str() + 4));
  w.controls().threads = threads;
  w.controls().gg = g_gg;
  if (g_refactor > 0) w.controls().solver.cholmod.refactor_iterations = g_refactor;
  set_solver(pre, w.controls().solver);
  auto step = [&] { return w.step(); };
  try {
    for (int s = 0; s < warmup; ++s) step();
    const auto t0 = std::chrono::steady_clock::now();
    while (r.steps < max_steps) {
      const StepStats st = step();
      ++r.steps;
      r.cuts += st.step_cuts;
      r.oc_per_step += st.open_close_iterations;
      r.cg_per_step += st.cg_iterations;
      r.factorisations_per_step += st.factorisations;
      std::snprintf(r.solver, sizeof r.solver, "%s", st.solver);
      r.detect += st.profile[Stage::DetectContacts];
      r.assemble += st.profile[Stage::Assemble];
      r.solve += st.profile[Stage::Solve];
      r.check += st.profile[Stage::CheckContacts];
      r.update += st.profile[Stage::Update];
      r.total += st.profile.total;
      r.contacts = st.contacts;
      if (std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count() > budget && r.steps >= 3) break;
    }
  } catch (const std::exception& e) {
    r.failed = true;
    std::snprintf(r.error, sizeof r.error, "%s", e.what());
  }
  r.blocks = static_cast<int>(w.block_count());
  if (r.steps > 0) {
    r.ms_per_step = r.total / r.steps * 1e3;
    r.oc_per_step /= r.steps;
    r.cg_per_step /= r.steps;
    r.factorisations_per_step /= r.steps;
  }
  rusage ru{};
  getrusage(RUSAGE_SELF, &ru);
  r.peak_rss_mb = ru.ru_maxrss / 1024.0;
  return r;
}

// The CHOLMOD factor of a: its sizes, the CPU ms of its analysis, of a numeric
// factorisation, of a solve with it and of a product A·x (the unit of the
// automatic choice's work, solver_choice.hpp), and CHOLMOD's peak memory.
std::string cholmod_row(const std::string& name, FillOrdering ordering, const BlockSparseMatrix& a, const VecX& b) {
  // CPU seconds of this thread (all of it runs here): less moved by a busy machine than the clock.
  auto now = [] {
    timespec t{};
    clock_gettime(CLOCK_THREAD_CPUTIME_ID, &t);
    return t.tv_sec + 1e-9 * t.tv_nsec;
  };
  auto ms_since = [&](double t) { return (now() - t) * 1e3; };
  CholmodFactor f;
  f.ordering = ordering;
  auto t = now();
  f.factorise(a);
  const double first = ms_since(t);
  const int repeats = 3;
  t = now();
  for (int k = 0; k < repeats; ++k) f.factorise(a);
  const double factor = ms_since(t) / repeats;
  VecX z;
  t = now();
  for (int k = 0; k < 10; ++k) f.solve(b, z);
  const double solve = ms_since(t) / 10;
  VecX y(b.size());
  t = now();
  for (int k = 0; k < 10; ++k) a.multiply_rows(0, a.rows(), b, y);
  const double product = ms_since(t) / 10;
  char line[256];
  std::snprintf(line, sizeof line, "%-10s %-6s %7d %9d %10.0f %10.1f %9.2f %9.2f %9.3f %9.3f %9.1f %9.2f\n",
                name.c_str(), ordering == FillOrdering::Metis ? "metis" : "amd", a.rows(), a.nonzero_blocks(),
                f.factor_entries(), f.factor_flops() / 1e6, first - factor, factor, solve, product,
                f.peak_bytes() / 1048576.0, f.peak_bytes() / 1024.0 / a.rows());
  return line;
}

// The linear solver alone: wall(N) stepped `steps` times (so that contacts
// have slid, opened and locked as they do), then its last system A·D = F
// solved from zero to 1e-10 with block-Jacobi and with multigrid PCG.
void solver_table(const std::vector<std::string>& scenes, int steps) {
  std::printf("\nCold PCG solves of the last system after %d+ steps at the full dt (1 thread, tolerance 1e-10):\n",
              steps);
  std::printf("%-10s %7s %9s %9s %9s %9s %9s %9s  %s\n", "scene", "blocks", "dt", "bj_iters", "bj_ms", "mg_iters",
              "mg_ms", "mg_setup", "levels");
  std::vector<std::string> cholmod_rows;
  for (const auto& scene : scenes) {
    if (scene.rfind("wall", 0) != 0) continue;
    World w;
    w = test::brick_wall(std::atoi(scene.c_str() + 4));
    w.controls().threads = 1;
    w.controls().solver.pcg.preconditioner = Preconditioning::Multigrid;
    // At least `steps` steps, then on until a step ran at the full Δt = g1
    // (early steps may have been cut while the wall settles).
    for (int s = 0; s < steps || (s < steps + 6 && w.last_stats().dt < w.controls().g1); ++s) w.step();
    const BlockSparseMatrix& a = w.last_matrix();
    const VecX& b = w.last_rhs();
    std::vector<Vec2> c;
    for (std::size_t i = 0; i < w.block_count(); ++i) c.push_back(w.block_centroid(static_cast<BlockId>(i)));
    auto time_solve = [&](PcgSolver& pcg, double& setup_ms) {
      pcg.tolerance = 1e-10;
      pcg.max_iterations = 100000;
      const auto t0 = std::chrono::steady_clock::now();
      pcg.set_operator(a);
      const auto t1 = std::chrono::steady_clock::now();
      VecX x = VecX::Zero(b.size());
      const SolveReport r = pcg.solve(b, x);
      const auto t2 = std::chrono::steady_clock::now();
      setup_ms = std::chrono::duration<double>(t1 - t0).count() * 1e3;
      return std::make_pair(r.iterations, std::chrono::duration<double>(t2 - t0).count() * 1e3);
    };
    double bj_setup = 0, mg_setup = 0;
    PcgSolver bj;
    const auto [bj_it, bj_ms] = time_solve(bj, bj_setup);
    auto mg = std::make_unique<Multigrid>();
    mg->set_block_centroids(c);
    Multigrid* mgp = mg.get();
    PcgSolver mgs(std::move(mg));
    const auto [mg_it, mg_ms] = time_solve(mgs, mg_setup);
    std::string levels;
    for (int l = 0; l < mgp->levels(); ++l) {
      if (l > 0) levels += ' ';
      levels += std::to_string(mgp->level_blocks(l));
    }
    std::printf("%-10s %7d %9.2e %9d %9.2f %9d %9.2f %9.2f  %s\n", display_name(scene).c_str(), a.rows(),
                w.last_stats().dt, bj_it, bj_ms, mg_it, mg_ms, mg_setup, levels.c_str());
    std::fflush(stdout);
    for (const FillOrdering o : {FillOrdering::Metis, FillOrdering::Amd})
      cholmod_rows.push_back(cholmod_row(display_name(scene), o, a, b));
  }
  std::printf("\nThe CHOLMOD factor of the same systems (ordering of the block graph; 1 thread, CPU ms):\n");
  std::printf("%-10s %-6s %7s %9s %10s %10s %9s %9s %9s %9s %9s %9s\n", "scene", "order", "blocks", "stored", "nnz(L)",
              "Mflop", "analyse", "factor", "solve", "product", "peakMB", "kB/block");
  for (const std::string& row : cholmod_rows) std::printf("%s", row.c_str());
}

// Runs in a child process so the peak RSS is the run's own.
Result run_isolated(const std::string& scene, int threads, const std::string& pre, int warmup, int steps,
                    double budget) {
  int fd[2];
  if (pipe(fd) != 0) return run(scene, threads, pre, warmup, steps, budget);
  const pid_t pid = fork();
  if (pid < 0) {
    close(fd[0]);
    close(fd[1]);
    return run(scene, threads, pre, warmup, steps, budget);
  }
  if (pid == 0) {
    close(fd[0]);
    const Result r = run(scene, threads, pre, warmup, steps, budget);
    const ssize_t n = write(fd[1], &r, sizeof r);
    close(fd[1]);
    _exit(n == static_cast<ssize_t>(sizeof r) ? 0 : 1);
  }
  close(fd[1]);
  Result r;
  std::size_t got = 0;
  while (got < sizeof r) {
    const ssize_t n = read(fd[0], reinterpret_cast<char*>(&r) + got, sizeof r - got);
    if (n <= 0) break;
    got += static_cast<std::size_t>(n);
  }
  close(fd[0]);
  int status = 0;
  waitpid(pid, &status, 0);
  if (got != sizeof r) {
    r = Result{};
    r.failed = true;
    std::snprintf(r.error, sizeof r.error, "child process died (status %d)", status);
  }
  return r;
}

std::vector<std::string> split(const std::string& s) {
  std::vector<std::string> out;
  std::size_t start = 0;
  while (start <= s.size()) {
    const std::size_t end = s.find(',', start);
    const std::string item = s.substr(start, end == std::string::npos ? std::string::npos : end - start);
    if (!item.empty()) out.push_back(item);
    if (end == std::string::npos) break;
    start = end + 1;
  }
  return out;
}

}  // namespace

int main(int argc, char** argv) {
  std::vector<std::string> scenes{"wall10", "wall20", "wall40"};
  bool solver = true, steps_table = true;
  std::vector<int> threads{1, 2};
  std::vector<std::string> pres{"auto"};
  int warmup = 2, steps = 30;
  double budget = 6;
  std::string csv;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    auto next = [&]() -> std::string {
      if (i + 1 >= argc) {
        std::fprintf(stderr, "%s needs a value\n", a.c_str());
        std::exit(2);
      }
      return argv[++i];
    };
    if (a == "--scenes") {
      scenes = split(next());
    } else if (a == "--threads") {
      threads.clear();
      for (const auto& t : split(next())) threads.push_back(std::atoi(t.c_str()));
    } else if (a == "--pre") {
      pres = split(next());
    } else if (a == "--warmup") {
      warmup = std::atoi(next().c_str());
    } else if (a == "--refactor") {
      g_refactor = std::atoi(next().c_str());
    } else if (a == "--gg") {
      g_gg = std::atof(next().c_str());
    } else if (a == "--steps") {
      steps = std::atoi(next().c_str());
    } else if (a == "--budget") {
      budget = std::atof(next().c_str());
    } else if (a == "--csv") {
      csv = next();
    } else if (a == "--solver-only") {
      steps_table = false;
    } else if (a == "--no-solver") {
      solver = false;
    } else {
      std::fprintf(stderr,
                   "usage: bench_engine [--scenes wall10,wall20,wall40] [--threads 1,2]\n"
                   "                    [--pre auto,pcg,bj,mg,chol] [--gg 0] [--refactor n] [--warmup 2] [--steps 30] "
                   "[--budget 6] [--csv file]\n"
                   "                    [--solver-only | --no-solver]\n");
      return 2;
    }
  }
  for (const auto& p : pres)
    if (p != "auto" && p != "pcg" && p != "bj" && p != "mg" && p != "chol") {
      std::fprintf(stderr, "unknown solver '%s' (auto, pcg, bj, mg, chol)\n", p.c_str());
      return 2;
    }
  for (const auto& s : scenes)
    if (s.rfind("wall", 0) != 0 || std::atoi(s.c_str() + 4) < 1) {
      std::fprintf(stderr, "unknown scene '%s' (wallN)\n", s.c_str());
      return 2;
    }

  if (!steps_table) {
    solver_table(scenes, 3);
    return 0;
  }
  std::FILE* out = csv.empty() ? nullptr : std::fopen(csv.c_str(), "w");
  if (out)
    std::fprintf(
        out,
        "scene,threads,pre,solver,blocks,contacts,steps,ms_per_step,block_steps_per_s,oc_per_step,cg_per_step,"
        "factorisations_per_step,cuts,detect_pct,assemble_pct,solve_pct,check_pct,update_pct,other_pct,peak_rss_mb\n");
  std::printf("%-10s %3s %-4s %-7s %7s %8s %5s %9s %11s %6s %8s %6s %4s  %6s %6s %6s %6s %6s %6s %8s\n", "scene", "thr",
              "pre", "solver", "blocks", "contacts", "steps", "ms/step", "blk-steps/s", "oc/st", "cg/st", "fac/st",
              "cuts", "detect", "asm", "solve", "check", "update", "other", "peakMB");
  for (const auto& scene : scenes)
    for (int t : threads)
      for (const auto& pre : pres) {
        const Result r = run_isolated(scene, t, pre, warmup, steps, budget);
        const std::string name = display_name(scene);
        if (r.failed) {
          std::printf("%-10s %3d %-4s failed: %s\n", name.c_str(), t, pre.c_str(), r.error);
          std::fflush(stdout);
          continue;
        }
        const double tot = r.total > 0 ? r.total : 1;
        const double other = r.total - r.detect - r.assemble - r.solve - r.check - r.update;
        const double bsps = r.ms_per_step > 0 ? r.blocks / (r.ms_per_step * 1e-3) : 0;
        std::printf(
            "%-10s %3d %-4s %-7s %7d %8d %5d %9.2f %11.0f %6.2f %8.1f %6.2f %4d  %5.1f%% %5.1f%% %5.1f%% %5.1f%% "
            "%5.1f%% %5.1f%% %8.1f\n",
            name.c_str(), t, pre.c_str(), r.solver, r.blocks, r.contacts, r.steps, r.ms_per_step, bsps, r.oc_per_step,
            r.cg_per_step, r.factorisations_per_step, r.cuts, 100 * r.detect / tot, 100 * r.assemble / tot,
            100 * r.solve / tot, 100 * r.check / tot, 100 * r.update / tot, 100 * other / tot, r.peak_rss_mb);
        std::fflush(stdout);
        if (out)
          std::fprintf(out, "%s,%d,%s,%s,%d,%d,%d,%.4f,%.1f,%.3f,%.2f,%.3f,%d,%.2f,%.2f,%.2f,%.2f,%.2f,%.2f,%.2f\n",
                       name.c_str(), t, pre.c_str(), r.solver, r.blocks, r.contacts, r.steps, r.ms_per_step, bsps,
                       r.oc_per_step, r.cg_per_step, r.factorisations_per_step, r.cuts, 100 * r.detect / tot,
                       100 * r.assemble / tot, 100 * r.solve / tot, 100 * r.check / tot, 100 * r.update / tot,
                       100 * other / tot, r.peak_rss_mb);
      }
  if (out) std::fclose(out);
  if (solver) solver_table(scenes, 3);
  return 0;
}
