#pragma once
// Progress of one section of the report over its units (a table model at a size, a sweep's scene,
// a stability scene and method, a model-accuracy case): each line names the unit, its number of
// how many, and from the second on the time left at the rate so far, e.g.
// "report: stability 14/42: block-squash: polar (about 3 min left)". Units may run in threads
// side by side (the stability study): begin() and finish() take a lock.
#include <chrono>
#include <mutex>
#include <ostream>
#include <string>

namespace corofem {

class SectionProgress {
 public:
  /// Lines begin "<tool>: <section> k/units: ".
  SectionProgress(std::ostream* out, std::string section, int units, std::string tool = "report");
  /// The next unit has begun: the prefix of its lines.
  std::string begin(const std::string& unit);
  void finish();  ///< the unit begun last (or any running one) has finished
  std::ostream* out() const { return out_; }

 private:
  std::ostream* out_;
  std::string section_, tool_;
  int units_, started_ = 0, done_ = 0;
  std::chrono::steady_clock::time_point start_ = std::chrono::steady_clock::now();
  std::mutex lock_;
};

}  // namespace corofem
