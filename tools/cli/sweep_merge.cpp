// `metrosync merge DIR...` (tools/cli/sweep.h): the regimes.csv of sweep shards joined into one,
// with maps; nothing is written unless every directory holds the same sweep.
#include <filesystem>
#include <functional>
#include <iostream>
#include <optional>

#include "sim/record/atomic_file.h"
#include "tools/cli/commands.h"
#include "tools/cli/sweep.h"
#include "tools/cli/sweep_folder.h"
#include "tools/cli/sweep_summary.h"
#include "tools/report/external_sort.h"
#include "tools/report/folder_lock.h"
#include "tools/report/outputs.h"
#include "tools/report/sweep_files.h"
#include "tools/report/sweep_maps.h"

namespace metrosync::cli {

namespace {

namespace fs = std::filesystem;

// Do two paths name one folder (both existing)?
bool sameFolder(const std::string& a, const std::string& b) {
  std::error_code ec;
  return fs::equivalent(a, b, ec) && !ec;
}

// No source given twice: the same folder under two names, or two folders holding the same shard.
void checkMergeSources(const SweepOptions& opt, const std::vector<SweepShard>& shards) {
  for (size_t i = 0; i < opt.dirs.size(); ++i)
    for (size_t j = i + 1; j < opt.dirs.size(); ++j) {
      if (sameFolder(opt.dirs[i], opt.dirs[j]))
        throw UsageError("merge: " + opt.dirs[j] + " is given twice (also as " + opt.dirs[i] + ")");
      if (shards[i].n > 1 && shards[i].k == shards[j].k && shards[i].n == shards[j].n)
        throw UsageError("merge: shard " + shards[i].text() + " is given twice: " + opt.dirs[i] +
                         " and " + opt.dirs[j]);
    }
}

// The rows of every grid point in ascending index (tools/report/external_sort.h: memory bounded
// whatever the number of rows): `row` gets each point's line once; sources that disagree on a
// point are a UsageError.
void forEachMergedRow(ExternalSort& rows, const std::vector<std::string>& dirs,
                      const std::function<void(long, const std::string&)>& row) {
  rows.forEachIndex([&](long g, const std::vector<std::string>& lines) {
    // "SOURCE\tLINE", sources in order: the first line of an index in each source wins
    const auto source = [](const std::string& l) { return std::stoul(l.substr(0, l.find('\t'))); };
    const auto text = [](const std::string& l) { return l.substr(l.find('\t') + 1); };
    std::size_t last_source = source(lines.front());
    for (const std::string& l : lines) {
      if (source(l) == last_source && &l != &lines.front()) continue;
      last_source = source(l);
      if (text(l) != text(lines.front()))
        throw UsageError("merge: " + dirs[source(lines.front())] + " and " + dirs[source(l)] +
                         " disagree on grid point " + std::to_string(g));
    }
    row(g, text(lines.front()));
  });
}

// Every source's manifest (all the same sweep: else a UsageError) and rows, added to `rows` as
// "SOURCE\tLINE"; the warnings of their regimes.csv said. Returns the first manifest.
SweepManifest readMergeSources(const SweepOptions& opt, ExternalSort& rows) {
  std::optional<SweepManifest> ref;
  std::string ref_dir;
  std::vector<SweepShard> shards;
  for (const auto& d : opt.dirs) {
    const SweepManifest m = readSweepManifest(d);
    shards.push_back(m.shard);
    if (!ref) {
      ref = m;
      ref_dir = d;
    } else if (const std::string diff = sweepDifference(*ref, m); !diff.empty()) {
      throw UsageError("merge: " + d + " is not the same sweep as " + ref_dir + ": " + diff);
    }
    const std::string source = std::to_string(shards.size() - 1) + "\t";
    const RegimesScan t =
        scanRegimesCsv(d + "/regimes.csv", ref->grid, ref->metronomes, "merge leaves the point out",
                       [&](const SweepPoint& p, const std::string& line) {
                         rows.add(p.index, source + line);
                         return true;
                       });
    for (const auto& w : t.warnings) std::cerr << "metrosync: warning: " << w << "\n";
  }
  checkMergeSources(opt, shards);
  return *ref;
}

int mergeImpl(const SweepOptions& opt) {
  if (opt.dirs.empty()) throw UsageError("merge: give the sweep output directories to join");
  // every manifest and every row first: nothing is written unless they all belong together
  ExternalSort rows(temporaryFolder());
  const SweepManifest ref = readMergeSources(opt, rows);
  SweepManifest merged = ref;
  merged.merged = true;
  merged.shard = SweepShard{};
  const SweepGrid& grid = merged.grid;
  const int n = merged.metronomes;
  const std::vector<size_t> map_axes = mapAxes(grid, opt.map);
  SweepTally tally;  // and the sources checked to agree, before anything is written
  forEachMergedRow(rows, opt.dirs, [&](long, const std::string& line) {
    tally.add(parseRegimesRow(grid, n, line));
  });

  const std::string path = opt.out.empty() ? defaultOutputDir(merged.rig_name, "merge") : opt.out;
  for (const auto& d : opt.dirs)
    if (sameFolder(path, d))
      throw UsageError("merge: --out " + path + " is one of the sources (" + d +
                       "): merging into it would replace that shard's files; choose another --out");
  std::optional<FolderLock> lock;
  if (fs::is_directory(path)) lock.emplace(path, "metrosync merge");
  OutputDir dir = [&] {
    try {
      OutputDir d(path);
      removeStaleSweepOutputs(d);
      return d;
    } catch (const std::runtime_error& e) {
      throw UsageError(std::string("--out: ") + e.what());
    }
  }();
  if (!lock) lock.emplace(path, "metrosync merge");
  {
    AtomicFile out(dir.file("regimes.csv"));
    out.writeLine(regimesHeader(grid, n));
    forEachMergedRow(rows, opt.dirs, [&](long, const std::string& line) { out.writeLine(line); });
    out.commit();
  }
  std::vector<std::string> files = {"regimes.csv"};
  const SweepPointSource points = [&](const std::function<void(const SweepPoint&)>& visit,
                                      const std::function<bool(const std::string&)>& wanted) {
    forEachRegimesRow(dir.file("regimes.csv"), grid, n, visit, wanted);
  };
  for (const auto& f :
       plotSweepMaps(dir, grid, n, points, mapTitle(merged), opt.plot_format, {}, map_axes))
    files.push_back(f);
  files.push_back("sweep.json");
  const bool complete = tally.done == grid.size();
  nlohmann::json status = statusJson(merged, grid.size(), tally, complete);
  status["sources"] = opt.dirs;
  status["files"] = files;
  writeSweepJson(dir, status);

  const long missing = grid.size() - tally.done;
  if (!opt.quiet)
    std::cout << "merged " << opt.dirs.size() << " sweep directories of " << merged.rig_name << " ("
              << modelTitle(merged.model) << "): " << tally.done << " of " << grid.size()
              << " points\n  regimes: " << countsText(tally) << "\nfiles: " << dir.path() << "/ ("
              << joined(files) << ")\n";
  if (missing > 0)
    std::cerr << "metrosync: warning: " << missing
              << " grid points are in none of the directories (white in the maps; sweep.json "
                 "says complete: false)\n";
  return kSuccess;
}

}  // namespace

int mergeCommand(const SweepOptions& opt) {
  try {
    return mergeImpl(opt);
  } catch (const SweepInputError& e) {
    throw UsageError(e.what());
  } catch (const FolderLockedError& e) {
    throw UsageError(e.what());
  }
}

}  // namespace metrosync::cli
