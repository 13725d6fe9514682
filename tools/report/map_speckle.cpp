#include "tools/report/map_speckle.h"

#include <map>
#include <sstream>

namespace metrosync {

MapSpeckle mapSpeckle(const std::string& dir, const std::string& map_keys) {
  MapSpeckle m;
  m.manifest = readSweepManifest(dir);
  const SweepGrid& grid = m.manifest.grid;
  m.axes = mapAxes(grid, map_keys);
  m.labels.assign(static_cast<size_t>(grid.size()), "");
  forEachRegimesRow(dir + "/regimes.csv", grid, m.manifest.metronomes, [&](const SweepPoint& p) {
    m.labels[static_cast<size_t>(p.index)] = p.regime;
  });
  m.cells = isolatedCells(grid, m.axes, m.labels);
  return m;
}

std::string speckleText(const MapSpeckle& m, bool list) {
  long points = 0;
  for (const auto& l : m.labels) points += !l.empty();
  std::map<std::string, long> kinds;
  for (const auto& c : m.cells) ++kinds[c.label + " in " + c.neighbours];
  std::ostringstream s;
  s << m.cells.size() << " isolated cells of " << points << " points";
  std::string sep = " (";
  for (const auto& [kind, count] : kinds) s << sep << kind << ": " << count, sep = ", ";
  s << (kinds.empty() ? "" : ")") << "\n";
  if (!list) return s.str();
  const SweepGrid& grid = m.manifest.grid;
  for (const auto& c : m.cells) {
    s << "  index " << c.index << ":";
    const std::vector<long> at = grid.coordinates(c.index);
    for (size_t a : m.axes) s << " " << grid.axes()[a].key << "=" << grid.axes()[a].text(at[a]);
    s << "  " << c.label << " in " << c.neighbours << "\n";
  }
  return s.str();
}

}  // namespace metrosync
