// Progress of long work, told to whoever listens: the CLI draws a bar or prints a line per
// phase on stderr (cli/progress_bar.h); a web front end could send the same events. The core
// calls it between pieces of work and never prints; a null pointer means nobody listens.
#pragma once

#include <cstddef>
#include <string>

namespace strand::slicer {

class Progress {
 public:
  virtual ~Progress() = default;
  // A new phase begins ("slicing layers"); `steps` is how many step() calls will count it
  // (0: not counted).
  virtual void phase(const std::string& name, std::size_t steps = 0) = 0;
  // `done` of the current phase's steps are finished. May be called often: keep it cheap.
  virtual void step(std::size_t done) = 0;
};

inline void progress_phase(Progress* p, const std::string& name, std::size_t steps = 0) {
  if (p) p->phase(name, steps);
}

inline void progress_step(Progress* p, std::size_t done) {
  if (p) p->step(done);
}

}  // namespace strand::slicer
