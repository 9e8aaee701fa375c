#include "core/Progress.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <iomanip>
#include <sstream>

namespace sl
{
namespace
{
std::ostream* gProgressStream = nullptr;

std::string seconds(double s)
{
  std::ostringstream text;
  text << std::fixed << std::setprecision(s < 10.0 ? 1 : 0) << s << " s";
  return text.str();
}
} // namespace

void setProgressStream(std::ostream* stream)
{
  gProgressStream = stream;
}

std::ostream* progressStream()
{
  return gProgressStream;
}

Progress::Progress(std::string what, std::string work, std::string unit, std::size_t total, std::ostream* out,
  ProgressSettings settings)
  : what_(std::move(what))
  , work_(std::move(work))
  , unit_(std::move(unit))
  , total_(total)
  , out_(out)
  , settings_(std::move(settings))
{
  start_ = now();
  lastLine_ = start_;
}

double Progress::now() const
{
  if (settings_.clock)
  {
    return settings_.clock();
  }
  return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count();
}

bool Progress::needsSync(std::size_t done) const
{
  if (out_ == nullptr)
  {
    return false;
  }
  if (done == 0)
  {
    return true; // before begin(): the first unit's time must not include earlier stages still queued
  }
  // The first unit is measured (unless it is the only one); after an estimate was printed, every unit, so that
  // progress lines and the final line tell the work done, not the commands queued. A unit is then at least
  // announceAfterSeconds / total long, against which a wait costs nothing.
  return measured_ ? announced_ : done < total_;
}

void Progress::begin()
{
  start_ = now();
  lastLine_ = start_;
}

void Progress::step(std::size_t done)
{
  if (out_ == nullptr || done == 0)
  {
    return;
  }
  const double t = now();
  const double elapsed = t - start_;
  const double expected = elapsed * static_cast<double>(total_) / static_cast<double>(done);
  if (!measured_)
  {
    measured_ = true;
    if (expected >= settings_.announceAfterSeconds && done < total_)
    {
      announced_ = true;
      lastLine_ = t;
      *out_ << "shadowlab: " << what_ << ": " << work_ << ", expect about " << seconds(expected)
            << " on this machine (measured: " << done << " " << unit_ << (done == 1 ? "" : "s") << " in "
            << seconds(elapsed) << ")"
            << std::endl;
    }
    return;
  }
  if (announced_ && done < total_ && t - lastLine_ >= settings_.intervalSeconds)
  {
    lastLine_ = t;
    *out_ << "shadowlab: " << what_ << ": " << done << "/" << total_ << " " << unit_ << "s, " << seconds(elapsed)
          << " elapsed, about " << seconds(std::max(0.0, expected - elapsed)) << " left" << std::endl;
  }
}

void Progress::finish()
{
  if (out_ != nullptr && (announced_ || (settings_.alwaysReportTotal && measured_)))
  {
    *out_ << "shadowlab: " << what_ << ": " << total_ << " " << unit_ << "s in " << seconds(now() - start_)
          << std::endl;
  }
  announced_ = false;
}

} // namespace sl
