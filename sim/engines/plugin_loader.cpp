#include "sim/engines/plugin_loader.h"

#include <dlfcn.h>
#include <unistd.h>

#include <cstdlib>
#include <map>
#include <mutex>

namespace metrosync {

namespace {

// the executable's folder, from /proc/self/exe ("" when it cannot be read)
std::string executableDirectory() {
  char buf[4096];
  const ssize_t n = readlink("/proc/self/exe", buf, sizeof buf - 1);
  if (n <= 0) return "";
  const std::string exe(buf, static_cast<size_t>(n));
  const size_t slash = exe.rfind('/');
  return slash == std::string::npos ? "" : exe.substr(0, slash);
}

bool readable(const std::string& path) {
  return access(path.c_str(), R_OK) == 0;
}

}  // namespace

std::vector<std::string> pluginDirectories() {
  const char* env = std::getenv("METROSYNC_PLUGIN_DIR");
  if (env && *env) return {env};
  const std::string exe_dir = executableDirectory();
  if (exe_dir.empty()) return {};
  // METROSYNC_PLUGIN_RELATIVE_DIR: the install tree's plugin folder relative to its bin folder
  return {exe_dir, exe_dir + "/" + METROSYNC_PLUGIN_RELATIVE_DIR};
}

void* loadPluginSymbol(const std::string& file, const char* symbol) {
  static std::mutex mutex;
  static std::map<std::string, void*> handles;  // never closed: code of theirs may still run
  std::lock_guard<std::mutex> lock(mutex);
  void*& handle = handles[file];
  const std::vector<std::string> dirs = pluginDirectories();
  if (!handle) {
    std::string searched;
    for (const std::string& d : dirs) {
      const std::string path = d + "/" + file;
      searched += (searched.empty() ? "" : ", ") + d;
      if (!readable(path)) continue;
      handle = dlopen(path.c_str(), RTLD_NOW | RTLD_LOCAL);
      if (!handle) throw PluginError("cannot load the plugin " + path + ": " + dlerror());
      break;
    }
    if (!handle)
      throw PluginError("the plugin " + file + " was not found (searched: " +
                        (searched.empty() ? std::string("nothing") : searched) +
                        "; METROSYNC_PLUGIN_DIR overrides); reinstall metrosync");
  }
  dlerror();
  void* sym = dlsym(handle, symbol);
  if (!sym) throw PluginError("the plugin " + file + " has no entry point " + symbol);
  return sym;
}

}  // namespace metrosync
