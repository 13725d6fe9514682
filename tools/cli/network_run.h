// `metrosync run` on a network of platforms (docs/networks.md): the direct or Simbody engine, the
// network's files (tools/report/network_files.h), summary.json with `platforms` and `network`. A
// network of one platform on the table, uncoupled, is today's rig and never comes here.
#pragma once

#include "tools/cli/commands.h"

namespace metrosync::cli {

// Does `opt` name a rig file that is a network today's single-platform path cannot run? A bad
// network throws RigError (exit 2) here, before anything is written.
bool isNetworkRun(const Options& opt);

// Runs it on the direct or the Simbody engine; `--model slow` and `--engine slowflow` are refused
// (UsageError, exit 2).
int runNetworkCommand(const Options& opt);

}  // namespace metrosync::cli
