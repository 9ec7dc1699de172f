#include "common/progress.h"

#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cstdio>

namespace dresskit::cli {
namespace {
double now() {
  return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count();
}
}  // namespace

Progress::Progress(std::string label, double total, std::string unit)
    : label_(std::move(label)), unit_(std::move(unit)), total_(total), terminal_(isatty(STDERR_FILENO) == 1) {}

Progress::~Progress() { finish(); }

void Progress::update(double done) {
  if (!terminal_ || !(total_ > 0.0)) return;
  const double t = now();
  if (drawn_ && t - last_draw_ < 0.1) return;
  last_draw_ = t;
  drawn_ = true;
  const double f = std::clamp(done / total_, 0.0, 1.0);
  constexpr int kWidth = 30;
  const int filled = static_cast<int>(f * kWidth);
  std::string bar(static_cast<std::size_t>(filled), '#');
  bar.append(static_cast<std::size_t>(kWidth - filled), '.');
  std::fprintf(stderr, "\r%s [%s] %3d %%  %.2f / %.2f %s", label_.c_str(), bar.c_str(),
               static_cast<int>(100.0 * f), done, total_, unit_.c_str());
  std::fflush(stderr);
}

void Progress::finish() {
  if (!drawn_) return;
  std::fprintf(stderr, "\r\033[K");  // clear the line: what follows starts clean
  std::fflush(stderr);
  drawn_ = false;
}

}  // namespace dresskit::cli
