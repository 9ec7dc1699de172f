// Alignment accuracy and speed: known-transform trials per angle with local ICP and with
// the global multi-start, the 10k-point single-part ICP time, error against run time, the
// Cramér–Rao bound of the rotation error per shape, and a check with sources sampled on the
// triangles instead of at the vertices.
// usage: bench_alignment [--trials N] [--csv docs/data/alignment_error_vs_time.csv] [--data DIR]
//                        [--only table|speed|tradeoff|bound|surface|export] [--angles 5,10,...]
//                        [--export DIR (pairs for Open3D)]
#include <Eigen/Dense>
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <string>

#include "bench_common.h"
#include "dresskit/testing/alignment_shapes.h"
#include "dresskit/testing/registration_trials.h"

using namespace dresskit::alignment;
using namespace dresskit::mannequin;
using namespace dresskit::mesh;

using namespace dresskit;

namespace {

// ICP as it was before the soft stage: hard correspondences only, strict coarse stages.
IcpOptions hard_only() {
  IcpOptions o;
  o.soft_neighbours = 0;
  o.coarse_epsilon_factor = 1.0;
  return o;
}

}  // namespace

int main(int argc, char** argv) {
  int trials = 20;
  std::string csv, data = DRESSKIT_DEFAULT_DATA_DIR, only, export_dir;
  std::vector<double> angles = {5, 10, 20, 30, 45, 60, 90, 135, 180};
  for (int i = 1; i + 1 < argc; i += 2) {
    if (!std::strcmp(argv[i], "--trials")) trials = std::atoi(argv[i + 1]);
    if (!std::strcmp(argv[i], "--csv")) csv = argv[i + 1];
    if (!std::strcmp(argv[i], "--data")) data = argv[i + 1];
    if (!std::strcmp(argv[i], "--only")) only = argv[i + 1];
    if (!std::strcmp(argv[i], "--export")) export_dir = argv[i + 1];
    if (!std::strcmp(argv[i], "--angles")) {
      angles.clear();
      for (const char* a = argv[i + 1]; *a;) {
        char* end = nullptr;
        angles.push_back(std::strtod(a, &end));
        a = *end ? end + 1 : end;
      }
    }
  }
  const std::vector<test::Shape> shapes = test::alignment_shapes(data, true);
  std::printf("shapes:");
  for (const auto& s : shapes) std::printf(" %s (%d points)", s.name.c_str(), s.points.size());
  std::printf(
      "\ntrials per angle and shape: %d; noise 0.5%% of diagonal, 10%% outliers, translation <= "
      "10%%\n\n",
      trials);

  if (only.empty() || only == "table") {
    std::printf(
        "| θ [°] | method | success | median rot. err. [°] | p95 rot. err. [°] | median transl. "
        "err. [%%] | "
        "mean time [ms] | success without the leg | failures by shape "
        "|\n|---|---|---|---|---|---|---|---|---|\n");
    for (double angle : angles) {
      // method 0: local ICP (defaults), 1: global multi-start, 2: local ICP without the soft
      // stage (hard correspondences only, as before it existed), on the same trials.
      for (int method = 0; method < 3; ++method) {
        const bool global = method == 1;
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
                                       : icp_align(trial.source, trial.target,
                                                   method == 2 ? hard_only() : IcpOptions{});
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
                          method == 1 ? "global" : (method == 2 ? "hard" : "local"), e.rotation_deg,
                          e.translation * 100, r.iterations, r.seconds * 1e3, r.fitness);
          }
          if (shape_failures)
            failures +=
                (failures.empty() ? "" : ", ") + shape.name + " " + std::to_string(shape_failures);
        }
        std::sort(rot.begin(), rot.end());
        std::sort(trans.begin(), trans.end());
        std::printf(
            "| %g | %s | %.0f%% (%d/%d) | %.3f | %.3f | %.3f | %.1f | %.0f%% (%d/%d) | %s |\n",
            angle,
            method == 1 ? "global (24 starts)"
                        : (method == 2 ? "local ICP, hard correspondences only" : "local ICP"),
            100.0 * ok / n, ok, n, rot[n / 2], rot[std::min(n - 1, static_cast<int>(0.95 * n))],
            trans[n / 2], 1e3 * seconds / n, 100.0 * ok_no_leg / std::max(1, n_no_leg), ok_no_leg,
            n_no_leg, failures.empty() ? "none" : failures.c_str());
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
    // CPU time of the calling thread (the machine is shared: wall time includes waiting).
    struct Variant {
      const char* name;
      IcpOptions options;
    };
    std::vector<Variant> variants;
    variants.push_back({"the default: 2500 driving points, soft stage", IcpOptions{}});
    variants.push_back(
        {"hard correspondences only, strict coarse stages (as before)", hard_only()});
    IcpOptions no_soft;
    no_soft.soft_neighbours = 0;
    variants.push_back({"hard correspondences only, loose coarse stages", no_soft});
    IcpOptions all_points;
    all_points.max_source_points = 10000;
    variants.push_back({"10000 driving points, soft stage", all_points});
    IcpOptions few;
    few.max_source_points = 1000;
    variants.push_back({"1000 driving points, soft stage", few});
    for (const Variant& v : variants) {
      std::mt19937 rng(99);
      std::vector<double> cpu, wall;
      int ok = 0, iterations = 0;
      for (int t = 0; t < 10; ++t) {
        TrialOptions to;
        to.angle_deg = 20;
        const Trial trial = make_trial(part, to, rng);
        const double c0 = bench::thread_cpu_seconds();
        const IcpResult r = icp_align(trial.source, trial.target, v.options);
        cpu.push_back(1e3 * (bench::thread_cpu_seconds() - c0));
        wall.push_back(r.seconds * 1e3);
        ok += trial_error(trial, r.transform).success();
        iterations += r.iterations;
      }
      std::sort(cpu.begin(), cpu.end());
      std::sort(wall.begin(), wall.end());
      std::printf(
          "10k-point ICP, %s: CPU median %.1f ms (min %.1f, max %.1f), wall median %.1f ms, "
          "%.1f iterations, success %d/10\n",
          v.name, cpu[5], cpu[0], cpu[9], wall[5], iterations / 10.0, ok);
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
  if (only == "bound") {
    // Cramér–Rao bound of the rotation error under the trial protocol: a source point carries
    // information about the pose only through its offset along the surface normal (σ = 0.5 % of
    // the diagonal, every vertex drawn once), so the Fisher information of the motion
    // (rotation vector about the centroid, translation) is Σ J Jᵀ / σ² with J = (p × n, n). The
    // rotation block of its inverse gives the smallest covariance any unbiased estimator reaches;
    // the share of trials within 0.5° follows by sampling that Gaussian.
    std::printf(
        "\n| shape | points | bound: rotation s.d. per principal axis [°] | median rot. err. "
        "[°] | p95 [°] | trials within 0.5° | ICP from the true pose, median rot. err. [°]: hard "
        "only / default |\n|---|---|---|---|---|---|---|\n");
    std::mt19937 rng(1);
    for (const auto& shape : shapes) {
      const PointSet& P = shape.points;
      const double sigma = 0.005 * bbox_diagonal(P.V);
      const Eigen::Vector3d c = P.V.colwise().mean().transpose();
      Eigen::Matrix<double, 6, 6> F = Eigen::Matrix<double, 6, 6>::Zero();
      for (int i = 0; i < P.size(); ++i) {
        const Eigen::Vector3d p = P.V.row(i).transpose() - c,
                              n = P.N.row(i).transpose().normalized();
        Eigen::Matrix<double, 6, 1> J;
        J << p.cross(n), n;
        F += J * J.transpose() / (sigma * sigma);
      }
      const Eigen::Matrix3d C = F.inverse().topLeftCorner<3, 3>();
      const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eig(C);
      const Eigen::Matrix3d L = Eigen::LLT<Eigen::Matrix3d>(C).matrixL();
      std::normal_distribution<double> gauss;
      std::vector<double> angle(100000);
      int within = 0;
      for (double& x : angle) {
        x = (L * Eigen::Vector3d(gauss(rng), gauss(rng), gauss(rng))).norm() * 180.0 / M_PI;
        within += x < 0.5;
      }
      std::sort(angle.begin(), angle.end());
      const Eigen::Vector3d sd = eig.eigenvalues().cwiseSqrt() * 180.0 / M_PI;
      // Where ICP's own minimum lies: started at the true pose (20 trials at θ = 20°), hard
      // correspondences drift away from it, the soft stage much less.
      std::vector<double> from_truth[2];
      std::mt19937 trial_rng(77);
      for (int t = 0; t < 20; ++t) {
        TrialOptions to;
        to.angle_deg = 20;
        const Trial trial = make_trial(P, to, trial_rng);
        for (int m = 0; m < 2; ++m)
          from_truth[m].push_back(
              trial_error(trial, icp_align(trial.source, trial.target,
                                           m ? IcpOptions{} : hard_only(), trial.truth)
                                     .transform)
                  .rotation_deg);
      }
      for (auto& v : from_truth) std::sort(v.begin(), v.end());
      std::printf("| %s | %d | %.3f, %.3f, %.3f | %.3f | %.3f | %.1f%% | %.3f / %.3f |\n",
                  shape.name.c_str(), P.size(), sd(2), sd(1), sd(0), angle[angle.size() / 2],
                  angle[angle.size() * 95 / 100], 100.0 * within / angle.size(), from_truth[0][10],
                  from_truth[1][10]);
    }
  }
  if (only == "surface") {
    // Outside the protocol: the source points are drawn uniformly on the triangles (as a scanner
    // would see the surface) instead of at the target's vertices, as many as there are vertices,
    // plus the same noise, outliers and motion. Checks that the soft stage does not rely on the
    // source points sitting at the target's vertices.
    LoadOptions dm;
    dm.units = Units::parse("dm");
    TriangleMesh body = load_mesh(data + "/bodies/mh_woman_young_average.obj", dm);
    apply_part_labels(body, data + "/labels/mh_body_part_labels.json");
    struct Surface {
      std::string name;
      Eigen::MatrixX3d V;
      Eigen::MatrixX3i F;
    };
    std::vector<Surface> surfaces{{"mh_woman body", body.V, body.F}};
    for (const std::string part : {"torso", "leg_left"}) {
      std::vector<int> map(body.num_vertices(), -1), keep;
      for (int v = 0; v < body.num_vertices(); ++v)
        if (body.labels(v) >= 0 && body.label_names[body.labels(v)] == part) {
          map[v] = static_cast<int>(keep.size());
          keep.push_back(v);
        }
      Surface s{"mh_woman " + part, Eigen::MatrixX3d(keep.size(), 3), {}};
      for (std::size_t k = 0; k < keep.size(); ++k) s.V.row(k) = body.V.row(keep[k]);
      std::vector<Eigen::RowVector3i> faces;
      for (int f = 0; f < body.F.rows(); ++f) {
        const Eigen::RowVector3i t(map[body.F(f, 0)], map[body.F(f, 1)], map[body.F(f, 2)]);
        if (t.minCoeff() >= 0) faces.push_back(t);
      }
      s.F.resize(faces.size(), 3);
      for (std::size_t k = 0; k < faces.size(); ++k) s.F.row(k) = faces[k];
      surfaces.push_back(s);
    }
    const TriangleMesh garment = load_mesh(data + "/garments/mh_female_casualsuit01.obj", dm);
    surfaces.push_back({"casualsuit01 garment", garment.V, garment.F});
    std::printf(
        "\nsources sampled on the triangles, θ in 5, 10, 20, 30°, %d trials each\n| noise | shape "
        "| method | success | median rot. err. [°] | p95 [°] |\n|---|---|---|---|---|---|\n",
        trials);
    for (double noise : {0.005, 0.0}) {
      for (const Surface& m : surfaces) {
        const PointSet target{m.V, vertex_normals(m.V, m.F)};
        const double diag = bbox_diagonal(m.V);
        std::vector<double> cumulative(m.F.rows());
        double area = 0.0;
        for (int f = 0; f < m.F.rows(); ++f) {
          const Eigen::RowVector3d a = m.V.row(m.F(f, 0)), b = m.V.row(m.F(f, 1)),
                                   c = m.V.row(m.F(f, 2));
          area += 0.5 * (b - a).cross(c - a).norm();
          cumulative[f] = area;
        }
        for (int method = 0; method < 2; ++method) {
          std::vector<double> rot;
          int ok = 0;
          for (double angle : {5.0, 10.0, 20.0, 30.0}) {
            std::mt19937 rng(7000 + static_cast<int>(angle));
            std::normal_distribution<double> gauss;
            std::uniform_real_distribution<double> uniform;
            for (int t = 0; t < trials; ++t) {
              TrialOptions to;
              to.angle_deg = angle;
              to.noise = 0.0;
              Trial trial = make_trial(target, to, rng);  // motion and outliers
              const Eigen::Matrix4d inverse = trial.truth.inverse();
              const int n = static_cast<int>(m.V.rows());
              Eigen::MatrixX3d X(n, 3);
              for (int i = 0; i < n; ++i) {
                const int f = static_cast<int>(
                    std::lower_bound(cumulative.begin(), cumulative.end(), uniform(rng) * area) -
                    cumulative.begin());
                double u = uniform(rng), v = uniform(rng);
                if (u + v > 1) {
                  u = 1 - u;
                  v = 1 - v;
                }
                const Eigen::RowVector3d a = m.V.row(m.F(f, 0));
                X.row(i) = a + u * (m.V.row(m.F(f, 1)) - a) + v * (m.V.row(m.F(f, 2)) - a);
                for (int d = 0; d < 3; ++d) X(i, d) += gauss(rng) * noise * diag;
              }
              trial.source.V.topRows(n) = transform_points(inverse, X);
              trial.source_centre = trial.source.V.topRows(n).colwise().mean().transpose();
              const IcpResult r =
                  icp_align(trial.source, trial.target, method ? hard_only() : IcpOptions{});
              const TrialError e = trial_error(trial, r.transform);
              rot.push_back(e.rotation_deg);
              ok += e.success();
            }
          }
          std::sort(rot.begin(), rot.end());
          const int n = static_cast<int>(rot.size());
          std::printf("| %.1f %% | %s | %s | %d/%d | %.3f | %.3f |\n", 100 * noise, m.name.c_str(),
                      method ? "hard correspondences only" : "default (soft stage)", ok, n,
                      rot[n / 2], rot[std::min(n - 1, n * 95 / 100)]);
          std::fflush(stdout);
        }
      }
    }
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
