// Run once at configure time (CMakeLists.txt, try_run): prints the Simbody library's own version
// for --version and summary.json, so that `metrosync` need not load Simbody to say it.
#include <simbody/internal/common.h>

#include <cstdio>

int main() {
  int major = 0, minor = 0, build = 0;
  SimTK_version_simbody(&major, &minor, &build);
  std::printf("%d.%d.%d\n", major, minor, build);
  return 0;
}
