// libFuzzer's entry, built once per target (tools/fuzz/fuzz.cmake): METROSYNC_FUZZ_TARGET names
// the body of tools/fuzz/fuzz_entries.h it runs. A finding aborts, so that libFuzzer keeps the
// input; any other exception escapes and is reported as a crash.
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string_view>

#include "tools/fuzz/fuzz_entries.h"

namespace {

void (*body())(std::string_view) {
  for (const auto& t : metrosync::fuzz::targets())
    if (std::strcmp(t.name, METROSYNC_FUZZ_TARGET) == 0) return t.run;
  std::abort();
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const unsigned char* data, std::size_t size) {
  static void (*const run)(std::string_view) = body();
  try {
    run({reinterpret_cast<const char*>(data), size});
  } catch (const metrosync::fuzz::FuzzFinding& e) {
    std::fprintf(stderr, "metrosync fuzz finding: %s\n", e.what());
    std::abort();
  }
  return 0;
}
