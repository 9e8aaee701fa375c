// Progress and an estimate for long runs (issue 27: reference-sm on a 2-million-triangle mesh or dcs on a 1 M
// triangle mesh ran for minutes without a line). A pass that works through `total` units in a CPU-side loop
// (reference-sm's K shadow maps, dcs's wedge chunks) makes one Progress and calls step() after each unit. After
// the first unit it knows the measured rate: when the whole run is then expected to take at least
// `announceAfterSeconds`, it prints the estimate, then a line every `intervalSeconds` with the time left, and a
// final line. Short runs print nothing. The pass must have waited for the GPU (glFinish) before step() for the
// clock to mean anything; needsSync() says when, so that short runs pay two waits and long ones one per unit.
#pragma once

#include <cstddef>
#include <functional>
#include <ostream>
#include <string>

namespace sl
{

// Where progress lines go: the CLI sets std::cerr unless --quiet; nullptr (the default: tests, bench's children)
// prints nothing and makes needsSync() false, so a silent run never waits for the GPU on progress's behalf.
void setProgressStream(std::ostream* stream);
std::ostream* progressStream();
// setProgressStream(stream) for a scope (a command's render), nullptr again after it.
struct ProgressStreamScope
{
  explicit ProgressStreamScope(std::ostream* stream) { setProgressStream(stream); }
  ~ProgressStreamScope() { setProgressStream(nullptr); }
  ProgressStreamScope(const ProgressStreamScope&) = delete;
  ProgressStreamScope& operator=(const ProgressStreamScope&) = delete;
};

struct ProgressSettings
{
  double announceAfterSeconds = 20.0; // expected total at or above this: the estimate and progress are printed
  double intervalSeconds = 5.0;       // between progress lines
  std::function<double()> clock;      // seconds; empty: std::chrono::steady_clock
  // finish() prints the total even when no estimate was printed (a run asked to show its progress, --progress,
  // whose first report came when it was already done).
  bool alwaysReportTotal = false;
};

class Progress
{
public:
  // `what`: "reference-sm"; `work`: the size in words ("2000000 triangles x 64 maps"); `unit`: "map" (a count of
  // `total` of them is printed as "12/64 maps").
  Progress(std::string what, std::string work, std::string unit, std::size_t total, std::ostream* out = progressStream(),
    ProgressSettings settings = {});
  // Whether the caller should wait for the GPU (glFinish) before step(done), or before begin() for done = 0:
  // before the start, after the first unit, and after every unit once the estimate was printed (never without a
  // stream; a short run waits twice).
  bool needsSync(std::size_t done) const;
  void begin();                // the clock starts (the constructor starts it too)
  void step(std::size_t done); // `done` units finished
  void finish();               // the final line, when the estimate was printed
  bool announced() const { return announced_; }

private:
  double now() const;
  std::string what_, work_, unit_;
  std::size_t total_;
  std::ostream* out_;
  ProgressSettings settings_;
  double start_ = 0.0;
  double lastLine_ = 0.0;
  bool measured_ = false;
  bool announced_ = false;
};

} // namespace sl
