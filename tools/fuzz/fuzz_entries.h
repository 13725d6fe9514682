// The fuzz targets' bodies (issue 39): each takes one input's bytes, runs it through a parser of
// metrosync and checks what comes back. A bad input may be refused, with the parser's own error
// and a located message; anything else -- another exception, a message without its place, a
// loaded result that breaks the parser's promises -- is a finding (FuzzFinding). libFuzzer's
// targets (tools/fuzz/targets/, built in build-fuzz: tools/setup.sh fuzz) abort on a finding, so
// that the input is kept; tests/fuzz runs every input of tools/fuzz/corpus/ through the same
// bodies in the ordinary build.
#pragma once

#include <cstddef>
#include <cstdint>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

namespace metrosync::fuzz {

// What a parser did that it must not do.
struct FuzzFinding : std::logic_error {
  using std::logic_error::logic_error;
};

// The input split at NUL bytes: the first part, then the others (empty ones kept).
std::vector<std::string> nulSeparated(std::string_view input);

// A rig (yaml/rig_loader.h): the YAML text before the first NUL, each later part a --set.
void rigLoader(std::string_view input);
// A network of platforms (yaml/network_loader.h), split as rigLoader's.
void networkLoader(std::string_view input);
// The key language (yaml/key_path.h): the input as a key, as KEY=VALUE, as a --set and as a
// --vary key of the default rig and of a network.
void keyPath(std::string_view input);
// The fit and measure data file (sim/analysis/fit/data_file.h).
void dataFile(std::string_view input);
// metrosync's whole command line parsed (every command, as tools/metrosync.cpp builds it), the
// arguments the NUL-separated parts; a sweep's --vary, --shard, --map and --random, a basin's
// --random then checked as the command does before it loads a rig.
void options(std::string_view input);

// The targets by name (the corpus's folder names): rig, network, keys, data, options.
struct Target {
  const char* name;
  void (*run)(std::string_view);
};
const std::vector<Target>& targets();

}  // namespace metrosync::fuzz
