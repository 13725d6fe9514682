// metrosync_isolated_cells DIR [--map KEY1,KEY2] [--list]: the isolated cells of a sweep's
// regime map (tools/report/map_speckle.h): cells whose four neighbours share one other label.
// Exit 0 with the count on stdout; 2 for a folder that is not a sweep.
#include <iostream>
#include <string>

#include "tools/report/map_speckle.h"

int main(int argc, char** argv) {
  std::string dir, map;
  bool list = false;
  for (int k = 1; k < argc; ++k) {
    const std::string a = argv[k];
    if (a == "--list") {
      list = true;
    } else if (a == "--map" && k + 1 < argc) {
      map = argv[++k];
    } else if (dir.empty() && a.rfind("--", 0) != 0) {
      dir = a;
    } else {
      std::cerr << "usage: metrosync_isolated_cells DIR [--map KEY1,KEY2] [--list]\n";
      return 2;
    }
  }
  if (dir.empty()) {
    std::cerr << "usage: metrosync_isolated_cells DIR [--map KEY1,KEY2] [--list]\n";
    return 2;
  }
  try {
    std::cout << metrosync::speckleText(metrosync::mapSpeckle(dir, map), list);
  } catch (const std::exception& e) {
    std::cerr << "metrosync_isolated_cells: error: " << e.what() << "\n";
    return 2;
  }
  return 0;
}
