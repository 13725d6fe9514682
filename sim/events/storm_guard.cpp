#include "sim/events/storm_guard.h"

#include <sstream>

namespace metrosync {

std::string StormGuard::why() const {
  std::ostringstream os;
  const Tier& t = tripped_ ? *tripped_ : burst_;
  os << "event storm: more than " << t.max_events << " events within " << t.window_periods
     << " fast periods";
  return os.str();
}

}  // namespace metrosync
