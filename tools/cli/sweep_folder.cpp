#include "tools/cli/sweep_folder.h"

#include <signal.h>
#include <unistd.h>

#include <cerrno>
#include <filesystem>
#include <iostream>
#include <set>

#include "tools/cli/commands.h"
#include "tools/report/envelope_store.h"
#include "tools/report/sweep_maps.h"

namespace metrosync::cli {

namespace {

namespace fs = std::filesystem;

// The files a sweep writes (besides the maps), for removing stale ones.
const std::vector<std::string>& sweepFileNames() {
  static const std::vector<std::string> names = {"regimes.csv", "sweep.json", "timings.csv",
                                                 kEnvelopeStoreName};
  return names;
}

}  // namespace

// Removes the sweep's own files left in `dir` by an earlier command, and the temporary files of
// commands that are no longer running; run's files too (every file in DIR then belongs to this
// command).
void removeStaleSweepOutputs(const OutputDir& dir) {
  dir.removeStaleOutputs();
  std::vector<std::string> names = sweepFileNames();
  for (const auto& m : sweepMapNames()) names.push_back(m);
  std::error_code ec;
  for (const auto& name : names) fs::remove(dir.file(name), ec);
  for (const auto& entry : fs::directory_iterator(dir.path(), ec)) {
    const std::string f = entry.path().filename().string();
    if (isSweepSliceMapName(f)) {  // regimes--KEY=VALUE.png: an N-D sweep's maps
      fs::remove(entry.path(), ec);
      continue;
    }
    for (const auto& name : names) {
      const std::string prefix = "." + name + ".";
      if (f.compare(0, prefix.size(), prefix) != 0 || f.size() < 6 ||
          f.compare(f.size() - 5, 5, ".part") != 0)
        continue;
      // ".NAME.<pid>.part" or ".NAME.<suffix>.<pid>.part": the pid is the last number
      const std::string core = f.substr(0, f.size() - 5);
      const std::string pid_text = core.substr(core.rfind('.') + 1);
      if (pid_text.empty() || pid_text.find_first_not_of("0123456789") != std::string::npos)
        continue;
      const long pid = std::stol(pid_text);
      if (pid != ::getpid() && ::kill(static_cast<pid_t>(pid), 0) != 0 && errno == ESRCH)
        fs::remove(entry.path(), ec);
    }
  }
}

bool checkResumable(const SweepOptions& opt, const SweepPlan& plan) {
  if (!opt.resume) return false;
  const std::string& path = plan.path;
  if (fs::exists(path + "/sweep.json")) {
    const SweepManifest old = readSweepManifest(path);
    std::string diff = sweepDifference(old, plan.manifest);
    if (diff.empty() && (old.shard.k != plan.shard.k || old.shard.n != plan.shard.n))
      diff = "it is shard " + old.shard.text() + ", not " + plan.shard.text();
    if (!diff.empty())
      throw UsageError("--resume: " + path + " holds another sweep: " + diff +
                       " (resume it with its own command line, or choose another --out)");
    return true;
  }
  if (fs::exists(plan.regimes_path))
    throw UsageError("--resume: " + path +
                     " has a regimes.csv but no sweep.json: cannot check "
                     "that it is this sweep");
  if (!opt.quiet)
    std::cerr << "metrosync: nothing to resume in " << path << "/: starting the sweep\n";
  return false;
}

std::set<long> storedEnvelopePoints(const std::string& store_path) {
  std::set<long> points;
  forEachStoredEnvelope(store_path,
                        [&](long g, const std::vector<std::string>&) { points.insert(g); });
  return points;
}

OutputDir openSweepDir(const std::string& path, bool resuming) {
  try {
    OutputDir d(path);
    if (!resuming) removeStaleSweepOutputs(d);
    return d;
  } catch (const std::runtime_error& e) {
    throw UsageError(std::string("--out: ") + e.what());
  }
}

}  // namespace metrosync::cli
