#include "sim/events/storm_guard.h"

#include <sstream>

namespace metrosync {

std::string StormGuard::why() const {
  std::ostringstream os;
  os << "event storm: more than " << max_events_ << " events within " << window_periods_
     << " fast periods";
  return os.str();
}

}  // namespace metrosync
