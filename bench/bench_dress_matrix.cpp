// `dress` over every sensible pairing of the shared data, run as a user runs it (the command-line
// tool, the defaults, units given, no label files), each case in its own process. Per case: pass,
// or every reason it fails; per group and in total: the pass rate and the CPU time's median and
// worst. Written to OUT.csv, one row per case.
//
// A case passes when all of these hold, each measured here from the files the run wrote:
// - exit 0, within the CPU-time limit (30 s; a run is killed after --timeout wall-clock seconds);
// - no dressed garment vertex deeper than 2 mm inside the body (generalised winding number);
// - each garment crosses itself (edge–triangle crossings) no more often dressed than as authored,
//   and garments worn together do not cross each other;
// - where a ground truth exists (MakeHuman's own refit of the outfit to the body, posed or not):
//   the mean vertex distance to it below 2 % of the body's height placed and 3 % dressed.
//
// Groups: `unposed` (each outfit on each MakeHuman body of its size class), `posed` (the same in
// four poses), `gc` (every outfit on GarmentCode's mean body in A- and T-pose, metres), `cross` (an
// outfit on a body of the other sex), `two` (two outfits at once, inferred layers), `units` (an
// outfit converted to metres on a body in decimetres).
//
//   bench_dress_matrix OUT.csv [--jobs 2] [--groups a,b] [--only SUBSTR,...] [--leave-out SUBSTR,...]
//                              [--timeout 120] [--limit 30] [--cli PATH] [--keep DIR] [--extra ARGS]
// `--only` keeps the cases whose name contains one of the texts, `--leave-out` drops them.
#include <signal.h>
#include <sys/resource.h>
#include <sys/types.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <map>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include "bench_common.h"
#include "dresskit/cloth/self_collision.h"
#include "dresskit/mesh/inside.h"
#include "dresskit/mesh/io.h"
#include "dresskit/testing/data.h"

using namespace dresskit;
namespace fs = std::filesystem;

namespace {

struct Garment {
  std::string outfit;     ///< e.g. female_casualsuit01 (the reference files' name)
  std::string path;       ///< as given to dress
  std::string units;      ///< as given to dress
  std::string reference;  ///< ground truth (MakeHuman's refit, decimetres), or ""
};

struct Case {
  std::string name, group;
  std::string body, body_units;
  std::vector<Garment> garments;
  std::vector<std::string> extra;  ///< further dress options
};

std::vector<std::string> split(const std::string& text) {
  std::vector<std::string> items;
  std::stringstream in(text);
  for (std::string item; std::getline(in, item, ',');)
    if (!item.empty()) items.push_back(item);
  return items;
}

bool contains_any(const std::string& name, const std::vector<std::string>& parts) {
  return std::any_of(parts.begin(), parts.end(), [&](const std::string& p) { return name.find(p) != std::string::npos; });
}

/// A MakeHuman outfit in metres (the file's positions divided by ten), written under `dir`.
std::string in_metres(const std::string& path_dm, const std::string& dir) {
  const fs::path out = fs::path(dir) / (fs::path(path_dm).stem().string() + "_m.obj");
  if (fs::exists(out)) return out.string();
  std::ifstream in(path_dm);
  std::ofstream o(out);
  for (std::string line; std::getline(in, line);) {
    if (line.rfind("v ", 0) == 0) {
      std::istringstream s(line.substr(2));
      double x = 0, y = 0, z = 0;
      s >> x >> y >> z;
      char buf[128];
      std::snprintf(buf, sizeof buf, "v %.9g %.9g %.9g", x / 10.0, y / 10.0, z / 10.0);
      o << buf << "\n";
    } else {
      o << line << "\n";
    }
  }
  return out.string();
}

/// The matrix, from the files of the data folder: MakeHuman outfits (garments/mh_*.obj), the
/// bodies each has a reference on (its size class), the posed bodies and references.
std::vector<Case> matrix(const std::string& data, const std::string& scratch) {
  std::vector<std::string> outfits;  // female_casualsuit01, ...
  for (const auto& e : fs::directory_iterator(data + "/garments")) {
    const std::string stem = e.path().stem().string();
    if (e.path().extension() == ".obj" && stem.rfind("mh_", 0) == 0) outfits.push_back(stem.substr(3));
  }
  std::sort(outfits.begin(), outfits.end());
  const std::vector<std::string> bodies{"mh_woman_young_average", "mh_man_young_average", "mh_girl_child_11y"};
  const std::vector<std::string> poses{"arms_down", "reach", "step_back", "knees_bent"};
  auto garment = [&](const std::string& outfit, const std::string& reference) {
    const std::string ref = data + "/" + reference;
    return Garment{outfit, data + "/garments/mh_" + outfit + ".obj", "dm",
                   !reference.empty() && fs::is_regular_file(ref) ? ref : ""};
  };
  std::vector<Case> cases;
  std::map<std::string, std::vector<std::string>> class_of;  // outfit → bodies it has references on
  for (const std::string& o : outfits)
    for (const std::string& b : bodies)
      if (fs::exists(data + "/reference/" + o + "__on__" + b + ".obj")) class_of[o].push_back(b);
  for (const std::string& o : outfits)
    for (const std::string& b : class_of[o]) {
      cases.push_back({o + "@" + b, "unposed", data + "/bodies/" + b + ".obj", "dm",
                       {garment(o, "reference/" + o + "__on__" + b + ".obj")}, {}});
      for (const std::string& p : poses) {
        const std::string body = data + "/posed/bodies/" + b + "__" + p + ".obj";
        if (!fs::exists(body)) continue;
        cases.push_back({o + "@" + b + "__" + p, "posed", body, "dm",
                         {garment(o, "posed/reference/" + o + "__on__" + b + "__" + p + ".obj")}, {}});
      }
    }
  for (const std::string& o : outfits)
    for (const std::string& b : {"gc_mean_all", "gc_mean_all_tpose"})
      cases.push_back({o + "@" + b, "gc", data + "/bodies/" + b + ".obj", "m", {garment(o, "")}, {}});
  // The first outfit of each sex on the adult body of the other.
  const auto first_of = [&](const std::string& sex) {
    for (const std::string& o : outfits)
      if (o.rfind(sex, 0) == 0) return o;
    return std::string();
  };
  const std::string female = first_of("female_"), male = first_of("male_");
  if (!male.empty()) cases.push_back({male + "@mh_woman_young_average", "cross", data + "/bodies/mh_woman_young_average.obj", "dm", {garment(male, "")}, {}});
  if (!female.empty()) cases.push_back({female + "@mh_man_young_average", "cross", data + "/bodies/mh_man_young_average.obj", "dm", {garment(female, "")}, {}});
  // Two outfits at once: the first two of each sex on their first body, layers inferred.
  for (const std::string& sex : {"female_", "male_"}) {
    std::vector<std::string> two;
    for (const std::string& o : outfits)
      if (o.rfind(sex, 0) == 0 && two.size() < 2) two.push_back(o);
    if (two.size() < 2 || class_of[two[0]].empty()) continue;
    const std::string b = class_of[two[0]][0];
    Case c{two[0] + "+" + two[1] + "@" + b, "two", data + "/bodies/" + b + ".obj", "dm", {}, {"--layers", "inferred"}};
    for (const std::string& o : two) c.garments.push_back(garment(o, "reference/" + o + "__on__" + b + ".obj"));
    cases.push_back(c);
  }
  // Units: the first outfit of each sex in metres on its first body in decimetres.
  for (const std::string& o : {female, male}) {
    if (o.empty() || class_of[o].empty()) continue;
    const std::string b = class_of[o][0];
    Garment g = garment(o, "reference/" + o + "__on__" + b + ".obj");
    g.path = in_metres(g.path, scratch);
    g.units = "m";
    cases.push_back({o + "_in_m@" + b, "units", data + "/bodies/" + b + ".obj", "dm", {g}, {}});
  }
  return cases;
}

struct Outcome {
  int exit_code = -1;
  double wall = 0.0, cpu = 0.0;
  bool timed_out = false;
  std::string last_error;  ///< the last line the run wrote on stderr
};

struct Running {
  pid_t pid = -1;
  std::size_t index = 0;
  std::chrono::steady_clock::time_point start;
};

std::vector<std::string> dress_args(const Case& c, const std::string& cli, const std::string& out,
                                    const std::vector<std::string>& extra) {
  std::vector<std::string> args{cli, "dress", c.body};
  for (const Garment& g : c.garments) args.push_back(g.path);
  args.insert(args.end(), {"--body-units", c.body_units, "--garment-units", c.garments[0].units, "-o", out});
  args.insert(args.end(), c.extra.begin(), c.extra.end());
  args.insert(args.end(), extra.begin(), extra.end());
  return args;
}

pid_t start(const std::vector<std::string>& args, const std::string& log) {
  const pid_t pid = fork();
  if (pid == 0) {
    setpgid(0, 0);
    if (std::FILE* f = std::freopen(log.c_str(), "w", stderr)) (void)f;
    if (std::FILE* f = std::freopen("/dev/null", "w", stdout)) (void)f;
    std::vector<char*> argv;
    for (const std::string& a : args) argv.push_back(const_cast<char*>(a.c_str()));
    argv.push_back(nullptr);
    execv(argv[0], argv.data());
    _exit(127);
  }
  return pid;
}

std::string last_line(const std::string& path) {
  std::ifstream in(path);
  std::string line, last;
  while (std::getline(in, line))
    if (line.rfind("dress-a-mesh: ", 0) == 0 && line.find("warning") == std::string::npos) last = line;
  return last;
}

double mean_distance(const Eigen::MatrixX3d& a, const Eigen::MatrixX3d& b) {
  return (a - b).rowwise().norm().mean();
}

/// Every reason the case fails, measured from its outputs ("" = passes), and the figures.
struct Judgement {
  std::string reasons;
  int inside = 0, crossings_authored = 0, crossings_dressed = 0, between = 0;
  double deepest = 0.0, placed_pct = -1.0, dressed_pct = -1.0;
};

Judgement judge(const Case& c, const Outcome& run, const std::string& out, double limit) {
  Judgement j;
  auto fail = [&](const std::string& why) { j.reasons += (j.reasons.empty() ? "" : "; ") + why; };
  if (run.timed_out) fail("killed after " + std::to_string(static_cast<int>(run.wall)) + " s");
  else if (run.exit_code != 0) fail("exit " + std::to_string(run.exit_code) + ": " + run.last_error);
  if (run.cpu > limit) fail("took " + std::to_string(static_cast<int>(run.cpu + 0.5)) + " s CPU");
  if (run.exit_code != 0) return j;
  mesh::LoadOptions body_units;
  body_units.units = mesh::Units::parse(c.body_units);
  const mesh::TriangleMesh body = mesh::load_mesh(c.body, body_units);
  const double height = body.V.col(1).maxCoeff() - body.V.col(1).minCoeff();
  const mesh::InsideTest inside(body);
  std::vector<Eigen::MatrixX3d> dressed;
  std::vector<Eigen::MatrixX3i> faces;
  for (const Garment& g : c.garments) {
    mesh::LoadOptions units;
    units.units = mesh::Units::parse(g.units);
    const std::string stem = fs::path(g.path).stem().string();
    const mesh::TriangleMesh authored = mesh::load_mesh(g.path, units);
    const mesh::TriangleMesh placed = mesh::load_mesh(out + "/" + stem + ".placed.obj", units);
    const mesh::TriangleMesh done = mesh::load_mesh(out + "/" + stem + ".dressed.obj", units);
    double deepest = 0.0;
    j.inside += inside.count_deeper(done.V, 0.002, &deepest);
    j.deepest = std::max(j.deepest, deepest);
    const int authored_crossings = cloth::count_intersections(authored.V, authored.F);
    const int dressed_crossings = cloth::count_intersections(done.V, authored.F);
    j.crossings_authored += authored_crossings;
    j.crossings_dressed += dressed_crossings;
    if (dressed_crossings > authored_crossings)
      fail(stem + " crosses itself " + std::to_string(dressed_crossings) + " times (" +
           std::to_string(authored_crossings) + " as authored)");
    if (!g.reference.empty()) {
      mesh::LoadOptions dm;
      dm.units = mesh::Units::parse("dm");
      const mesh::TriangleMesh reference = mesh::load_mesh(g.reference, dm);
      const double placed_pct = 100.0 * mean_distance(placed.V, reference.V) / height;
      const double dressed_pct = 100.0 * mean_distance(done.V, reference.V) / height;
      j.placed_pct = std::max(j.placed_pct, placed_pct);
      j.dressed_pct = std::max(j.dressed_pct, dressed_pct);
      char buf[160];
      if (placed_pct >= 2.0) {
        std::snprintf(buf, sizeof buf, "%s placed %.2f %% from the ground truth", stem.c_str(), placed_pct);
        fail(buf);
      }
      if (dressed_pct >= 3.0) {
        std::snprintf(buf, sizeof buf, "%s dressed %.2f %% from the ground truth", stem.c_str(), dressed_pct);
        fail(buf);
      }
    }
    dressed.push_back(done.V);
    faces.push_back(authored.F);
  }
  if (j.inside > 0) {
    char buf[160];
    std::snprintf(buf, sizeof buf, "%d vertices deeper than 2 mm inside the body (deepest %.1f mm)", j.inside,
                  1e3 * j.deepest);
    fail(buf);
  }
  if (dressed.size() > 1) {
    Eigen::MatrixX3d all(0, 3);
    Eigen::MatrixX3i all_faces(0, 3);
    for (std::size_t k = 0; k < dressed.size(); ++k) {
      const Eigen::Index offset = all.rows();
      all.conservativeResize(all.rows() + dressed[k].rows(), 3);
      all.bottomRows(dressed[k].rows()) = dressed[k];
      all_faces.conservativeResize(all_faces.rows() + faces[k].rows(), 3);
      all_faces.bottomRows(faces[k].rows()) = faces[k].array() + static_cast<int>(offset);
    }
    j.between = cloth::count_intersections(all, all_faces) - j.crossings_dressed;
    if (j.between > 0) fail("the garments cross each other " + std::to_string(j.between) + " times");
  }
  return j;
}

}  // namespace

int main(int argc, char** argv) {
  if (argc < 2 || argv[1][0] == '-') {
    std::cerr << "usage: bench_dress_matrix OUT.csv [--jobs 2] [--groups a,b] [--only S,...] [--leave-out S,...] "
                 "[--timeout 120] [--limit 30] [--cli PATH] [--keep DIR] [--extra ARGS]\n";
    return 64;
  }
  int jobs = 2;
  double timeout = 120.0, limit = 30.0;
  std::vector<std::string> groups, only, leave_out, extra;
  std::string cli = (fs::path(argv[0]).parent_path() / "dress-a-mesh").string(), keep;
  for (int a = 2; a + 1 < argc; a += 2) {
    const std::string key = argv[a], value = argv[a + 1];
    if (key == "--jobs") jobs = std::max(1, std::stoi(value));
    else if (key == "--groups") groups = split(value);
    else if (key == "--only") only = split(value);
    else if (key == "--leave-out") leave_out = split(value);
    else if (key == "--timeout") timeout = std::stod(value);
    else if (key == "--limit") limit = std::stod(value);
    else if (key == "--cli") cli = value;
    else if (key == "--keep") keep = value;
    else if (key == "--extra") {
      std::istringstream in(value);
      for (std::string w; in >> w;) extra.push_back(w);
    } else {
      std::cerr << "bench_dress_matrix: unknown option " << key << "\n";
      return 64;
    }
  }
  const std::string data = testing::data_dir();
  const fs::path scratch = keep.empty() ? fs::temp_directory_path() / ("dresskit-matrix-" + std::to_string(getpid()))
                                        : fs::path(keep);
  fs::create_directories(scratch);
  std::vector<Case> cases;
  for (const Case& c : matrix(data, scratch.string())) {
    if (!groups.empty() && std::find(groups.begin(), groups.end(), c.group) == groups.end()) continue;
    if (!only.empty() && !contains_any(c.name, only)) continue;
    if (!leave_out.empty() && contains_any(c.name, leave_out)) continue;
    cases.push_back(c);
  }
  std::cout << "bench_dress_matrix: " << cases.size() << " cases, " << jobs << " at a time, on " << bench::cpu_model()
            << "\n";
  std::vector<Outcome> outcomes(cases.size());
  std::vector<Running> running;
  std::size_t next = 0, done = 0;
  std::ofstream csv(argv[1]);
  csv << "case,group,pass,exit,cpu_s,wall_s,inside_2mm,deepest_mm,crossings_authored,crossings_dressed,"
         "crossings_between,placed_pct,dressed_pct,reasons\n";
  std::map<std::string, std::pair<int, int>> per_group;
  std::map<std::string, std::vector<double>> times;
  int passed = 0;
  auto folder = [&](std::size_t i) { return (scratch / cases[i].name).string(); };
  while (done < cases.size()) {
    while (running.size() < static_cast<std::size_t>(jobs) && next < cases.size()) {
      fs::remove_all(folder(next));
      running.push_back({start(dress_args(cases[next], cli, folder(next), extra), folder(next) + ".log"), next,
                         std::chrono::steady_clock::now()});
      ++next;
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(50));
    for (auto it = running.begin(); it != running.end();) {
      Outcome& o = outcomes[it->index];
      const double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - it->start).count();
      int status = 0;
      rusage usage{};
      pid_t r = wait4(it->pid, &status, WNOHANG, &usage);
      if (r == 0 && wall > timeout) {
        kill(-it->pid, SIGKILL);
        r = wait4(it->pid, &status, 0, &usage);
        o.timed_out = true;
      }
      if (r == 0) {
        ++it;
        continue;
      }
      o.wall = wall;
      o.cpu = static_cast<double>(usage.ru_utime.tv_sec + usage.ru_stime.tv_sec) +
              1e-6 * static_cast<double>(usage.ru_utime.tv_usec + usage.ru_stime.tv_usec);
      o.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
      o.last_error = last_line(folder(it->index) + ".log");
      const Case& c = cases[it->index];
      Judgement j;
      try {
        j = judge(c, o, folder(it->index), limit);
      } catch (const std::exception& e) {
        j.reasons = std::string("outputs unreadable: ") + e.what();
      }
      const bool pass = j.reasons.empty();
      passed += pass;
      per_group[c.group].first += pass;
      per_group[c.group].second += 1;
      times[c.group].push_back(o.cpu);
      times["all"].push_back(o.cpu);
      std::string quoted = j.reasons;
      std::replace(quoted.begin(), quoted.end(), '"', '\'');
      csv << c.name << ',' << c.group << ',' << pass << ',' << o.exit_code << ',' << o.cpu << ',' << o.wall << ','
          << j.inside << ',' << 1e3 * j.deepest << ',' << j.crossings_authored << ',' << j.crossings_dressed << ','
          << j.between << ',' << j.placed_pct << ',' << j.dressed_pct << ",\"" << quoted << "\"\n"
          << std::flush;
      char line[96];
      std::snprintf(line, sizeof line, "%-58s %5.1f s  ", c.name.c_str(), o.cpu);
      std::cout << line << (pass ? "pass" : "FAIL: " + j.reasons) << std::endl;
      ++done;
      it = running.erase(it);
    }
  }
  std::cout << "\ngroup        pass        CPU median   worst\n";
  for (const auto& [group, counts] : per_group) {
    const std::vector<double>& t = times[group];
    char line[128];
    std::snprintf(line, sizeof line, "%-12s %3d / %-3d   %8.1f s %8.1f s", group.c_str(), counts.first, counts.second,
                  bench::median(t), *std::max_element(t.begin(), t.end()));
    std::cout << line << "\n";
  }
  if (!cases.empty()) {
    const std::vector<double>& t = times["all"];
    char line[128];
    std::snprintf(line, sizeof line, "%-12s %3d / %-3zu   %8.1f s %8.1f s", "all", passed, cases.size(),
                  bench::median(t), *std::max_element(t.begin(), t.end()));
    std::cout << line << "\n";
  }
  if (keep.empty()) fs::remove_all(scratch);
  return 0;
}
