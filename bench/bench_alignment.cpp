// Alignment accuracy and speed (issue 6): known-transform trials per angle with local ICP and with
// the global multi-start, the 10k-point single-part ICP time, and error against run time.
// usage: bench_alignment [--trials N] [--csv docs/data/alignment_error_vs_time.csv] [--data DIR]
//                        [--only table|speed|tradeoff|export] [--export DIR (pairs for Open3D)]
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <string>

#include "alignment/alignment_shapes.h"
#include "dresskit/alignment/evaluation.h"

using namespace dresskit;

int main(int argc, char** argv) {
  int trials = 20;
  std::string csv, data = DRESSKIT_DEFAULT_DATA_DIR, only, export_dir;
  for (int i = 1; i + 1 < argc; i += 2) {
    if (!std::strcmp(argv[i], "--trials")) trials = std::atoi(argv[i + 1]);
    if (!std::strcmp(argv[i], "--csv")) csv = argv[i + 1];
    if (!std::strcmp(argv[i], "--data")) data = argv[i + 1];
    if (!std::strcmp(argv[i], "--only")) only = argv[i + 1];
    if (!std::strcmp(argv[i], "--export")) export_dir = argv[i + 1];
  }
  const std::vector<test::Shape> shapes = test::alignment_shapes(data, true);
  std::printf("shapes:");
  for (const auto& s : shapes) std::printf(" %s (%d points)", s.name.c_str(), s.points.size());
  std::printf(
      "\ntrials per angle and shape: %d; noise 0.5%% of diagonal, 10%% outliers, translation <= "
      "10%%\n\n",
      trials);

  const double angles[] = {5, 10, 20, 30, 45, 60, 90, 135, 180};
  if (only.empty() || only == "table") {
    std::printf(
        "| θ [°] | method | success | median rot. err. [°] | p95 rot. err. [°] | median transl. "
        "err. [%%] | "
        "mean time [ms] | success without the leg | failures by shape "
        "|\n|---|---|---|---|---|---|---|---|---|\n");
    for (double angle : angles) {
      for (int global = 0; global < 2; ++global) {
        std::vector<double> rot, trans;
        double seconds = 0.0;
        int ok = 0, n = 0, ok_no_leg = 0, n_no_leg = 0;
        std::string failures;
        std::mt19937 rng(1000 + static_cast<int>(angle));
        for (const auto& shape : shapes) {
          if (std::getenv("DRESSKIT_BENCH_SHAPE") &&
              shape.name.find(std::getenv("DRESSKIT_BENCH_SHAPE")) == std::string::npos)
            continue;
          int shape_failures = 0;
          const bool leg = shape.name.find("leg") != std::string::npos;
          for (int t = 0; t < trials; ++t) {
            TrialOptions o;
            o.angle_deg = angle;
            const Trial trial = make_trial(shape.points, o, rng);
            const auto start = std::chrono::steady_clock::now();
            const IcpResult r = global ? global_align(trial.source, trial.target).result
                                       : icp_align(trial.source, trial.target);
            const Eigen::Matrix4d& T = r.transform;
            seconds +=
                std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
            const TrialError e = trial_error(trial, T);
            rot.push_back(e.rotation_deg);
            trans.push_back(e.translation * 100);
            ok += e.success();
            ++n;
            shape_failures += !e.success();
            if (!leg) {
              ok_no_leg += e.success();
              ++n_no_leg;
            }
            if (std::getenv("DRESSKIT_BENCH_VERBOSE"))
              std::printf("  %s: %s θ=%g %s rot %.3f° transl %.3f%% it %d %.0f ms fit %.2f\n",
                          e.success() ? "ok" : "FAIL", shape.name.c_str(), angle,
                          global ? "global" : "local", e.rotation_deg, e.translation * 100,
                          r.iterations, r.seconds * 1e3, r.fitness);
          }
          if (shape_failures)
            failures +=
                (failures.empty() ? "" : ", ") + shape.name + " " + std::to_string(shape_failures);
        }
        std::sort(rot.begin(), rot.end());
        std::sort(trans.begin(), trans.end());
        std::printf(
            "| %g | %s | %.0f%% (%d/%d) | %.3f | %.3f | %.3f | %.1f | %.0f%% (%d/%d) | %s |\n",
            angle, global ? "global (24 starts)" : "local ICP", 100.0 * ok / n, ok, n, rot[n / 2],
            rot[std::min(n - 1, static_cast<int>(0.95 * n))], trans[n / 2], 1e3 * seconds / n,
            100.0 * ok_no_leg / std::max(1, n_no_leg), ok_no_leg, n_no_leg,
            failures.empty() ? "none" : failures.c_str());
        std::fflush(stdout);
      }
    }
  }
  if (only.empty() || only == "speed") {
    // 10k-point single part: the GarmentCode body's torso+head part, 10 000 points, θ = 20°.
    TriangleMesh gc = load_mesh(data + "/bodies/gc_mean_all.obj");
    apply_part_labels(gc, data + "/labels/gc_body_segmentation.json");
    PointSet part = test::part_points(gc, "body");
    std::printf("\nsingle part 'body' of gc_mean_all: %d points, first 10000 used\n", part.size());
    part.V.conservativeResize(std::min(10000, part.size()), 3);
    part.N.conservativeResize(part.V.rows(), 3);
    // The last run: the default points with 10× looser translation and fitness epsilons.
    for (int points : {2500, 10000, 1000, -2500}) {
      IcpOptions o;
      o.max_source_points = std::abs(points);
      if (points < 0) o.translation_epsilon = o.fitness_epsilon = 1e-4;
      std::mt19937 rng(99);
      std::vector<double> ms;
      int ok = 0;
      for (int t = 0; t < 10; ++t) {
        TrialOptions to;
        to.angle_deg = 20;
        const Trial trial = make_trial(part, to, rng);
        const IcpResult r = icp_align(trial.source, trial.target, o);
        ms.push_back(r.seconds * 1e3);
        ok += trial_error(trial, r.transform).success();
      }
      std::sort(ms.begin(), ms.end());
      std::printf(
          "10k-point ICP (%d of 10000 source points%s): median %.1f ms, min %.1f ms, max %.1f ms, "
          "success %d/10\n",
          std::abs(points),
          points < 0 ? ", epsilons 1e-4"
                     : (points == IcpOptions{}.max_source_points ? ", the default" : ""),
          ms[5], ms[0], ms[9], ok);
    }
  }
  if (only.empty() || only == "tradeoff") {
    // Error against run time: max iterations per stage × source points, θ = 20°, MakeHuman body.
    std::FILE* out = csv.empty() ? nullptr : std::fopen(csv.c_str(), "w");
    if (out)
      std::fprintf(out,
                   "max_iterations,source_points,mean_ms,median_rotation_deg,median_translation_"
                   "percent,success\n");
    std::printf("\nerror against run time (θ = 20°, %s):\n",
                shapes[2 % shapes.size()].name.c_str());
    for (int points : {500, 1000, 2500, 10000}) {
      for (int iterations : {1, 2, 3, 5, 8, 12, 20, 40}) {
        IcpOptions o;
        o.max_iterations = iterations;
        o.max_source_points = points;
        std::mt19937 rng(5);
        std::vector<double> rot, trans;
        double seconds = 0.0;
        int ok = 0;
        for (int t = 0; t < trials; ++t) {
          TrialOptions to;
          to.angle_deg = 20;
          const Trial trial = make_trial(shapes[2 % shapes.size()].points, to, rng);
          const IcpResult r = icp_align(trial.source, trial.target, o);
          const TrialError e = trial_error(trial, r.transform);
          seconds += r.seconds;
          rot.push_back(e.rotation_deg);
          trans.push_back(100 * e.translation);
          ok += e.success();
        }
        std::sort(rot.begin(), rot.end());
        std::sort(trans.begin(), trans.end());
        const int n = static_cast<int>(rot.size());
        std::printf(
            "  %5d points, %2d iterations/stage: %.1f ms, median rot %.3f°, transl %.3f%%, success "
            "%d/%d\n",
            points, iterations, 1e3 * seconds / n, rot[n / 2], trans[n / 2], ok, n);
        if (out)
          std::fprintf(out, "%d,%d,%.3f,%.5f,%.5f,%.3f\n", iterations, points, 1e3 * seconds / n,
                       rot[n / 2], trans[n / 2], static_cast<double>(ok) / n);
      }
    }
    if (out) std::fclose(out);
  }
  if (!export_dir.empty()) {
    // The same kind of pairs for scripts/bench_open3d_icp.py, with dresskit's result on each.
    std::filesystem::create_directories(export_dir);
    std::FILE* summary = std::fopen((export_dir + "/dresskit.csv").c_str(), "w");
    std::fprintf(summary, "pair,angle,rotation_deg,translation_percent,seconds\n");
    int index = 0;
    for (double angle : {5.0, 10.0, 20.0, 30.0}) {
      std::mt19937 rng(2000 + static_cast<int>(angle));
      for (const auto& shape : shapes) {
        TrialOptions to;
        to.angle_deg = angle;
        const Trial trial = make_trial(shape.points, to, rng);
        const IcpResult r = icp_align(trial.source, trial.target);
        const TrialError e = trial_error(trial, r.transform);
        char name[32];
        std::snprintf(name, sizeof name, "pair_%03d", index++);
        std::FILE* f = std::fopen((export_dir + "/" + name + ".txt").c_str(), "w");
        for (int k = 0; k < 16; ++k) std::fprintf(f, "%.17g ", trial.truth(k / 4, k % 4));
        std::fprintf(f, "\n%.17g %.17g %.17g\n%.17g\n", trial.source_centre.x(),
                     trial.source_centre.y(), trial.source_centre.z(), trial.diagonal);
        std::fclose(f);
        f = std::fopen((export_dir + "/" + name + "_source.xyz").c_str(), "w");
        for (Eigen::Index i = 0; i < trial.source.V.rows(); ++i)
          std::fprintf(f, "%.9g %.9g %.9g\n", trial.source.V(i, 0), trial.source.V(i, 1),
                       trial.source.V(i, 2));
        std::fclose(f);
        f = std::fopen((export_dir + "/" + name + "_target.xyzn").c_str(), "w");
        for (Eigen::Index i = 0; i < trial.target.V.rows(); ++i)
          std::fprintf(f, "%.9g %.9g %.9g %.6g %.6g %.6g\n", trial.target.V(i, 0),
                       trial.target.V(i, 1), trial.target.V(i, 2), trial.target.N(i, 0),
                       trial.target.N(i, 1), trial.target.N(i, 2));
        std::fclose(f);
        std::fprintf(summary, "%s,%g,%.6f,%.6f,%.6f\n", name, angle, e.rotation_deg,
                     100 * e.translation, r.seconds);
        std::printf("exported %s (%s, θ = %g°)\n", name, shape.name.c_str(), angle);
      }
    }
    std::fclose(summary);
  }
  return 0;
}
