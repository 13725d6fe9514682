// SIGINT and SIGTERM during a long command: the running simulation stops at its next row, its
// files kept and marked incomplete (tools/report/outputs.h, FileSink::requestStop).
#pragma once

namespace metrosync::cli {

// Installs SIGINT/SIGTERM handlers that ask the running simulation to stop (files are kept and
// marked incomplete); a second signal kills the process as usual.
void installStopHandlers();

}  // namespace metrosync::cli
