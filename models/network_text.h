// How messages name a network of platforms: "a network of 1 platform", "a network of 3
// platforms" (one phrase for the loader's and the commands' messages and titles).
#pragma once

#include <cstddef>
#include <string>

namespace metrosync {

// "network of N platform(s)", the noun agreeing with N.
inline std::string networkOfPlatforms(std::size_t platforms) {
  return "network of " + std::to_string(platforms) + (platforms == 1 ? " platform" : " platforms");
}

}  // namespace metrosync
