// The platform's state under a set-valued (dry) friction law: stuck, or sliding one way.
#pragma once

namespace metrosync {

enum class PlatformMode : int { SlipNegative = -1, Stuck = 0, SlipPositive = 1 };

}  // namespace metrosync
