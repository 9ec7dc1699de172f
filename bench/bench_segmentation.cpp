// Segmentation benchmark on gc_mean_all (23 752 vertices):
//  1. end to end (load + segment_mesh) on one thread, median of the repetitions, with the phases
//  and
//     the eigen residual max ‖L x − λ x‖;
//  2. error against run time over the eigen-solver's tolerance and subspace size (ncv): time, eigen
//     residual, and label agreement with the reference run (tolerance 1e-12, ncv 60) → CSV;
//  3. with --export DIR: the affinity matrix (Matrix Market), plain spectral clustering labels and
//     times of the same pipeline without clean-up or over-segmentation, for bench/bench_sklearn.py.
// Usage: bench_segmentation [--reps N] [--csv OUT.csv] [--export DIR]
// Data from DRESSKIT_DATA_DIR or ../shared/data. Run it pinned to one core: taskset -c 0 ….
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "bench_common.h"
#include "dresskit/mesh/io.h"
#include "dresskit/segmentation/graph.h"
#include "dresskit/segmentation/metrics.h"
#include "dresskit/segmentation/segment.h"

using namespace dresskit;
using namespace dresskit::mesh;
using namespace dresskit::segmentation;
using bench::median;

namespace {

double seconds_since(std::chrono::steady_clock::time_point t) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t).count();
}

SegmentationOptions body_options() {
  SegmentationOptions o;
  o.parts = 6;
  return o;
}

// The affinity restricted to vertices with an edge (a vertex without a face is not segmented);
// index[v] = row of vertex v, or −1.
void write_matrix_market(const std::string& path, const MeshGraph& graph, std::vector<int>& index) {
  index.assign(graph.num_vertices, -1);
  int rows = 0;
  for (int e = 0; e < graph.num_edges(); ++e) index[graph.from(e)] = index[graph.to(e)] = 0;
  for (int& i : index)
    if (i == 0) i = rows++;
  std::ofstream out(path);
  out << "%%MatrixMarket matrix coordinate real symmetric\n";
  out << "% dresskit segmentation affinity of gc_mean_all (build_mesh_graph defaults)\n";
  out << rows << " " << rows << " " << graph.num_edges() << "\n";
  out.precision(17);
  for (int e = 0; e < graph.num_edges(); ++e)  // lower triangle: row > column, 1-based
    out << index[graph.to(e)] + 1 << " " << index[graph.from(e)] + 1 << " " << graph.affinity(e)
        << "\n";
}

void write_labels(const std::string& path, const Eigen::VectorXi& labels,
                  const std::vector<int>& index) {
  std::ofstream out(path);
  for (int i = 0; i < labels.size(); ++i)
    if (index[i] >= 0) out << labels(i) << "\n";
}

}  // namespace

int main(int argc, char** argv) {
  int reps = 7;
  std::string csv_path, export_dir;
  for (int i = 1; i + 1 < argc; i += 2) {
    const std::string flag = argv[i];
    if (flag == "--reps") reps = std::max(1, std::atoi(argv[i + 1]));
    if (flag == "--csv") csv_path = argv[i + 1];
    if (flag == "--export") export_dir = argv[i + 1];
  }
  const char* env = std::getenv("DRESSKIT_DATA_DIR");
  const std::string data = env ? env : DRESSKIT_DEFAULT_DATA_DIR;
  const std::string path = data + "/bodies/gc_mean_all.obj";
  std::printf("machine: %s, one thread; median of %d runs\n", bench::cpu_model().c_str(), reps);

  // 1. End to end.
  std::vector<double> load, total, graph, eigen, clustering, residual;
  TriangleMesh mesh;
  SegmentationResult reference_run;
  for (int r = 0; r < reps; ++r) {
    const auto t0 = std::chrono::steady_clock::now();
    mesh = load_mesh(path);
    load.push_back(seconds_since(t0));
    reference_run = segment_mesh(mesh, body_options());
    total.push_back(seconds_since(t0));
    graph.push_back(reference_run.seconds.graph);
    eigen.push_back(reference_run.seconds.eigen);
    clustering.push_back(reference_run.seconds.clustering);
  }
  std::printf("gc_mean_all: %d vertices, %d faces, %d parts\n", mesh.num_vertices(),
              mesh.num_faces(), reference_run.parts_chosen);
  std::printf(
      "end to end (load + segment): %.0f ms  [load %.0f, graph %.0f, eigen %.0f, clustering %.0f "
      "ms]\n",
      median(total) * 1e3, median(load) * 1e3, median(graph) * 1e3, median(eigen) * 1e3,
      median(clustering) * 1e3);
  std::printf("eigen residual max |Lx - lx| = %.2e (%d Lanczos restarts)\n",
              reference_run.eigen_residual, reference_run.eigen_iterations);

  // 2. Error against run time over tolerance × ncv.
  SegmentationOptions tight = body_options();
  tight.eigen.tolerance = 1e-12;
  tight.eigen.ncv = 60;
  const SegmentationResult reference = segment_mesh(mesh, tight);
  std::FILE* csv = csv_path.empty() ? nullptr : std::fopen(csv_path.c_str(), "w");
  if (!csv_path.empty() && !csv) {
    std::fprintf(stderr, "cannot write %s\n", csv_path.c_str());
    return 3;
  }
  if (csv)
    std::fprintf(
        csv,
        "tolerance,ncv,converged,seconds_total,seconds_eigen,eigen_residual,agreement,mean_iou\n");
  std::printf("%9s %4s %9s %9s %10s %9s %8s\n", "tol", "ncv", "total ms", "eigen ms", "residual",
              "agreement", "mean IoU");
  for (double tol : {1e-1, 1e-2, 1e-4, 1e-6, 1e-8, 1e-10, 1e-12})
    for (int ncv : {10, 12, 16, 24, 40}) {
      SegmentationOptions o = body_options();
      o.eigen.tolerance = tol;
      o.eigen.ncv = ncv;
      o.eigen.max_iterations = 300;
      std::vector<double> t_total, t_eigen;
      SegmentationResult r;
      bool converged = true;
      for (int k = 0; k < std::max(1, reps / 2) && converged; ++k) {
        try {
          r = segment_mesh(mesh, o);
          t_total.push_back(r.seconds.total);
          t_eigen.push_back(r.seconds.eigen);
        } catch (const EigenSolverError&) {
          converged = false;
        }
      }
      const LabelComparison c =
          converged ? compare_labels(r.vertex_labels, reference.vertex_labels) : LabelComparison{};
      std::printf("%9.0e %4d %9.0f %9.0f %10.2e %9.4f %8.4f%s\n", tol, ncv, median(t_total) * 1e3,
                  median(t_eigen) * 1e3, converged ? r.eigen_residual : 0.0, c.agreement,
                  c.mean_iou, converged ? "" : "  (did not converge)");
      if (csv)
        std::fprintf(csv, "%g,%d,%d,%.6f,%.6f,%.6e,%.6f,%.6f\n", tol, ncv, converged ? 1 : 0,
                     median(t_total), median(t_eigen), converged ? r.eigen_residual : 0.0,
                     c.agreement, c.mean_iou);
    }
  if (csv) std::fclose(csv);

  // 3. The same affinity for scikit-learn, and plain spectral clustering (no clean-up, no merging).
  if (!export_dir.empty()) {
    std::filesystem::create_directories(export_dir);
    const MeshGraph g = build_mesh_graph(mesh.V, mesh.F);
    std::vector<int> index;
    write_matrix_market(export_dir + "/gc_affinity.mtx", g, index);
    SegmentationOptions plain = body_options();
    plain.cleanup = false;
    plain.over_segmentation = 0;
    plain.boundary_band = 0.0;  // eigen + k-means only: none of the boundary steps
    plain.limb_tip_fraction = 0.0;
    plain.symmetry_tolerance = 0.0;
    plain.split_skirts = false;
    plain.grow_limbs = false;
    std::vector<double> t;
    SegmentationResult r;
    for (int k = 0; k < reps; ++k) {
      r = segment_mesh(mesh, plain);
      t.push_back(r.seconds.eigen + r.seconds.clustering);
    }
    write_labels(export_dir + "/gc_labels_plain.txt", r.vertex_labels, index);
    write_labels(export_dir + "/gc_labels_final.txt", reference_run.vertex_labels, index);
    std::ofstream timing(export_dir + "/gc_plain_seconds.txt");
    timing << median(t) << "\n";
    std::printf(
        "exported %s/gc_affinity.mtx; plain spectral clustering (eigen + k-means) %.0f ms\n",
        export_dir.c_str(), median(t) * 1e3);
  }
  return 0;
}
