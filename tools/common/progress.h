#pragma once
// A progress line on stderr for long runs, drawn only when stderr is a terminal (never into a log
// or a pipe): "label  [#####.....]  52 %  1.04 / 2.00 s simulated".
#include <string>

namespace dresskit::cli {

class Progress {
 public:
  /// total: the amount that is 100 % (e.g. simulated seconds); unit: what it counts, for the line.
  Progress(std::string label, double total, std::string unit);
  ~Progress();  ///< ends the line if one was drawn
  /// Redraws at most ten times a second.
  void update(double done);
  void set_total(double total) { total_ = total; }
  bool terminal() const { return terminal_; }
  void finish();

 private:
  std::string label_, unit_;
  double total_ = 0.0, last_draw_ = -1.0;
  bool drawn_ = false, terminal_ = false;
};

}  // namespace dresskit::cli
