// `cmake --install` and the Debian package (tools/install/, docs/install.md): every file lands
// where the docs say, the generated man page and completions list exactly the commands and options
// the binary's own --help lists, the package declares its library dependencies, and the installed
// binary works from its installed rigs, giving the same results as the build tree's.
#include <gtest/gtest.h>

#include <cstdio>
#include <filesystem>
#include <regex>
#include <set>
#include <string>

#include "tests/common/run_metrosync.h"

namespace {

namespace fs = std::filesystem;
using metrosync::testing_support::CommandResult;
using metrosync::testing_support::scratchDir;
using metrosync::testing_support::shellQuote;
using metrosync::testing_support::slurp;

// Runs a shell command; stdout and stderr together.
CommandResult sh(const std::string& cmd) {
  CommandResult r;
  FILE* p = ::popen(("{ " + cmd + "; } 2>&1 </dev/null").c_str(), "r");
  if (!p) return r;
  char buf[4096];
  size_t n;
  while ((n = std::fread(buf, 1, sizeof buf, p)) > 0) r.out.append(buf, n);
  const int status = ::pclose(p);
  r.code = WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
  return r;
}

const fs::path kBuild = fs::path(METROSYNC_BINARY).parent_path();

// The sub-commands the binary's --help lists (read here independently of tools/install).
std::set<std::string> commandsOfHelp(const std::string& bin) {
  const CommandResult help = sh(shellQuote(bin) + " --help");
  std::set<std::string> commands;
  const size_t at = help.out.find("Subcommands:");
  if (at == std::string::npos) return commands;
  std::regex line("\\n  ([a-z][a-z-]*) ");
  const std::string rest = help.out.substr(at);
  for (std::sregex_iterator it(rest.begin(), rest.end(), line), end; it != end; ++it)
    commands.insert((*it)[1]);
  return commands;
}

// The short result of a rig: `scale --json` (every scaled parameter) from one binary.
std::string scaleJson(const std::string& bin, const std::string& rig) {
  return sh(shellQuote(bin) + " scale --json " + shellQuote(rig)).out;
}

// The installed binary and its installed plugins: all three there, and the simbody engine runs
// through the installed plugin, found from the binary's own location (bin/../<libdir>/metrosync),
// not the build tree's.
void expectPluginsWork(const fs::path& prefix, const std::string& bin, const std::string& rig,
                       const std::string& out) {
  std::set<std::string> plugins;
  for (const auto& e : fs::recursive_directory_iterator(prefix))
    if (e.path().extension() == ".so" && e.path().parent_path().filename() == "metrosync")
      plugins.insert(e.path().filename().string());
  for (const char* f : {"metrosync-simbody.so", "metrosync-ceres.so", "metrosync-animate.so"})
    EXPECT_EQ(plugins.count(f), 1u) << f << " not installed";
  const CommandResult simbody =
      sh("env -u METROSYNC_PLUGIN_DIR " + shellQuote(bin) + " run " + shellQuote(rig) +
         " --engine simbody --set simulation.duration=2 --quiet --no-plot --out " +
         shellQuote(out + "/simbody"));
  EXPECT_EQ(simbody.code, 0) << simbody.out;
  EXPECT_TRUE(fs::is_regular_file(out + "/simbody/summary.json"));
  // the loader's trace names the installed plugin, not the build tree's
  const CommandResult traced =
      sh("LD_DEBUG=libs " + shellQuote(bin) + " run " + shellQuote(rig) +
         " --engine simbody --set simulation.duration=0.5 --quiet --no-plot --out " +
         shellQuote(out + "/traced"));
  EXPECT_NE(traced.out.find(prefix.string()), std::string::npos);
  EXPECT_EQ(traced.out.find(kBuild.string() + "/metrosync-simbody.so"), std::string::npos);
}

// The Python module under `prefix` (when the build made one, tools/python/python.cmake): in the
// folder that Debian's python3 searches when the prefix is `system_prefix` (/usr/local for
// `cmake --install`, /usr for the package); imported from there (not from the build tree) in
// another folder, it runs a rig given as a dict with a wildcard override.
void expectPythonModuleWorks(const fs::path& prefix, const std::string& system_prefix,
                             const std::string& elsewhere) {
  if (!fs::exists(kBuild / "python/metrosync/__init__.py")) return;
  fs::path site;
  for (const auto& e : fs::recursive_directory_iterator(prefix))
    if (e.path().filename() == "__init__.py" && e.path().parent_path().filename() == "metrosync")
      site = e.path().parent_path().parent_path();
  ASSERT_FALSE(site.empty()) << "no metrosync/__init__.py under " << prefix;
  site = fs::weakly_canonical(site);  // as Python names it (scratch paths may hold "//")
  const std::string there =
      (fs::path(system_prefix) / site.lexically_relative(fs::weakly_canonical(prefix))).string();
  const std::string path =
      sh("/usr/bin/python3 -c 'import sys; print(*sys.path, end=chr(32))'").out;
  EXPECT_NE((" " + path).find(" " + there + " "), std::string::npos) << there << " not in " << path;
  bool so = false;
  for (const auto& e : fs::directory_iterator(site / "metrosync"))
    so = so || e.path().filename().string().rfind("_metrosync.cpython-", 0) == 0;
  EXPECT_TRUE(so) << "no _metrosync module in " << site;
  fs::create_directories(elsewhere);
  const std::string code =
      "import metrosync\n"
      "rig = {'units': 'scaled', 'epsilon': 0.05, 'platform': {'friction': {'law': 'coulomb', "
      "'mu': 0.3}}, 'metronomes': [{'nu': 0.5, 'J': 2.0, 'theta_c': 0.9, 'start': {'A': 2.0, "
      "'phi': 0.0}}, "
      "{'nu': 0.5, 'J': 2.0, 'theta_c': 0.9, 'start': {'A': 2.0, 'phi': 3.0}}], 'simulation': "
      "{'tau': 20}}\n"
      "r = metrosync.run(metrosync.load_rig(rig, {'metronomes.*.nu': 0.6}), model='slow', tau=20)\n"
      "print(metrosync.__file__, len(r.envelope['tau']))\n";
  const CommandResult py = sh("cd " + shellQuote(elsewhere) +
                              " && env -u PYTHONPATH PYTHONPATH=" + shellQuote(site.string()) +
                              " /usr/bin/python3 -c " + shellQuote(code));
  ASSERT_EQ(py.code, 0) << py.out;
  EXPECT_EQ(py.out.rfind(site.string(), 0), 0u) << py.out;  // the installed module
}

// The man page, the bash completion and metrosync-mpi where the system finds them: `man` with the
// prefix's bin on PATH (man-db maps it to PREFIX/share/man) and with -M; bash-completion's own
// loader with the prefix's share in XDG_DATA_DIRS (its default holds /usr/local/share and
// /usr/share); metrosync-mpi beside metrosync when the build has it.
void expectFoundWhereTheSystemLooks(const fs::path& p, const std::set<std::string>& commands) {
  const std::string bin = shellQuote((p / "bin").string()), share = (p / "share").string();
  const CommandResult where = sh("env -u MANPATH PATH=" + bin + ":$PATH man -w metrosync");
  EXPECT_EQ(where.out, (p / "share/man/man1/metrosync.1.gz").string() + "\n");
  const CommandResult page =
      sh("MANWIDTH=100 man -M " + shellQuote(share + "/man") + " metrosync | col -b");
  ASSERT_EQ(page.code, 0) << page.out;
  for (const std::string& c : commands)
    EXPECT_NE(page.out.find("metrosync " + c), std::string::npos) << c;
  // what the program is today: the description names the full model's engines, the default
  // first (sim/engines/engine.h), not Simbody alone
  const size_t description = page.out.find("DESCRIPTION");
  const std::string intro = page.out.substr(description, page.out.find("OPTIONS") - description);
  EXPECT_NE(intro.find("direct (the default)"), std::string::npos) << intro;
  EXPECT_NE(intro.find("simbody"), std::string::npos) << intro;
  EXPECT_EQ(intro.find("Simbody multibody system"), std::string::npos) << intro;

  const std::string loader = "/usr/share/bash-completion/bash_completion";
  if (!fs::exists(loader)) {
    ADD_FAILURE() << "bash-completion is not installed (tools/setup.sh installs it)";
  } else {
    const CommandResult complete =
        sh("XDG_DATA_DIRS=" + shellQuote(share) + " bash -c 'source " + loader +
           " && __load_completion metrosync && complete -p metrosync'");
    EXPECT_EQ(complete.code, 0) << complete.out;
    EXPECT_NE(complete.out.find("-F _metrosync metrosync"), std::string::npos) << complete.out;
  }
  if (fs::exists(kBuild / "metrosync-mpi")) {  // built when MPI is found (tools/cli/mpi.cmake)
    const fs::path mpi = p / "bin/metrosync-mpi";
    ASSERT_TRUE(fs::is_regular_file(mpi));
    const CommandResult help = sh(shellQuote(mpi.string()) + " --help");
    EXPECT_EQ(help.code, 0) << help.out;
    EXPECT_NE(help.out.find("sweep"), std::string::npos) << help.out;
  }
}

TEST(Install, PutsTheBinaryManPageCompletionsRigsAndDocsInPlace) {
  const std::string prefix = scratchDir("install", "prefix");
  const CommandResult inst =
      sh("cmake --install " + shellQuote(kBuild.string()) + " --prefix " + shellQuote(prefix));
  ASSERT_EQ(inst.code, 0) << inst.out;
  const fs::path p(prefix);
  const std::string bin = (p / "bin/metrosync").string();
  ASSERT_TRUE(fs::is_regular_file(bin));
  EXPECT_TRUE(fs::is_regular_file(p / "share/metrosync/rigs/experiment.yaml"));
  EXPECT_TRUE(fs::is_regular_file(p / "share/doc/metrosync/README.md"));
  EXPECT_TRUE(fs::is_regular_file(p / "share/doc/metrosync/docs/README.md"));

  // completions: every sub-command of --help, in both shells' scripts
  const std::set<std::string> commands = commandsOfHelp(bin);
  ASSERT_GE(commands.size(), 5u);
  const std::string bash = slurp((p / "share/bash-completion/completions/metrosync").string());
  const std::string zsh = slurp((p / "share/zsh/vendor-completions/_metrosync").string());
  for (const std::string& c : commands) {
    EXPECT_NE(bash.find("    " + c + ") "), std::string::npos) << c;
    EXPECT_NE(zsh.find("    " + c + ") "), std::string::npos) << c;
  }
  EXPECT_EQ(
      sh("bash -n " + shellQuote((p / "share/bash-completion/completions/metrosync").string()))
          .code,
      0);

  // the man page renders and has a section per sub-command
  const fs::path man = p / "share/man/man1/metrosync.1.gz";
  ASSERT_TRUE(fs::is_regular_file(man));
  const CommandResult page = sh("MANWIDTH=100 man -l " + shellQuote(man.string()) + " | col -b");
  ASSERT_EQ(page.code, 0) << page.out;
  for (const std::string& c : commands)
    EXPECT_NE(page.out.find("metrosync " + c), std::string::npos) << c;

  expectFoundWhereTheSystemLooks(p, commands);

  // the installed binary on an installed rig equals the build tree's
  const std::string rig = (p / "share/metrosync/rigs/experiment.yaml").string();
  const std::string installed = scaleJson(bin, rig);
  EXPECT_NE(installed.find("\"epsilon\""), std::string::npos) << installed;
  EXPECT_EQ(installed, scaleJson(METROSYNC_BINARY, rig));
  expectPluginsWork(p, bin, rig, scratchDir("install", "plugin_runs", true));
  expectPythonModuleWorks(p, "/usr/local", scratchDir("install", "python_elsewhere", true));
}

TEST(Install, DebianPackageDeclaresItsDependenciesAndRunsFromItsFiles) {
  const std::string out = scratchDir("install", "deb", true);
  const CommandResult pack =
      sh("cd " + shellQuote(kBuild.string()) + " && cpack -G DEB -B " + shellQuote(out));
  ASSERT_EQ(pack.code, 0) << pack.out;
  std::string deb;
  for (const auto& e : fs::directory_iterator(out))
    if (e.path().extension() == ".deb") deb = e.path().string();
  ASSERT_FALSE(deb.empty()) << pack.out;

  const std::string depends = sh("dpkg-deb -f " + shellQuote(deb) + " Depends").out;
  for (const char* lib : {"libsimbody", "libyaml-cpp", "libstdc++6", "gnuplot"})
    EXPECT_NE(depends.find(lib), std::string::npos) << lib << " missing in: " << depends;
  const bool python = fs::exists(kBuild / "python/metrosync/__init__.py");
  if (python) {  // the module imports numpy and is made for one Python version
    for (const char* dep : {"python3-numpy", "python3 (>= 3.", "python3 (<< 3."})
      EXPECT_NE(depends.find(dep), std::string::npos) << dep << " missing in: " << depends;
  }

  const std::string files = sh("dpkg-deb -c " + shellQuote(deb)).out;
  for (const char* f : {"./usr/bin/metrosync", "./usr/share/man/man1/metrosync.1.gz",
                        "./usr/share/bash-completion/completions/metrosync",
                        "./usr/share/metrosync/rigs/experiment.yaml"})
    EXPECT_NE(files.find(f), std::string::npos) << f;
  // nothing outside /usr
  std::regex entry("\\s(\\./[^\\s]*)");
  for (std::sregex_iterator it(files.begin(), files.end(), entry), end; it != end; ++it) {
    const std::string path = (*it)[1];
    EXPECT_TRUE(path == "./" || path.rfind("./usr/", 0) == 0 || path == "./usr") << path;
  }

  // unpacked into a scratch root, its binary runs on its own rigs
  const std::string root = out + "/root";
  ASSERT_EQ(sh("dpkg -x " + shellQuote(deb) + " " + shellQuote(root)).code, 0);
  const std::string bin = root + "/usr/bin/metrosync";
  const std::string rig = root + "/usr/share/metrosync/rigs/experiment.yaml";
  EXPECT_EQ(scaleJson(bin, rig), scaleJson(METROSYNC_BINARY, rig));
  const CommandResult run =
      sh(shellQuote(bin) + " run " + shellQuote(rig) +
         " --set simulation.duration=5 --quiet --out " + shellQuote(out + "/run"));
  EXPECT_EQ(run.code, 0) << run.out;
  EXPECT_TRUE(fs::is_regular_file(out + "/run/summary.json"));
  expectPluginsWork(root + "/usr", bin, rig, out + "/plugin_runs");
  if (fs::exists(kBuild / "metrosync-mpi")) {
    const CommandResult mpi = sh(shellQuote(root + "/usr/bin/metrosync-mpi") + " --help");
    EXPECT_EQ(mpi.code, 0) << mpi.out;
  }
  if (python) expectPythonModuleWorks(root + "/usr", "/usr", out + "/python_elsewhere");
}

}  // namespace
