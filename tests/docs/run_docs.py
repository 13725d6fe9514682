#!/usr/bin/env python3
"""Docs that run (issue 37): every command shown in README.md and docs/**/*.md, run with its exit
code checked (ctest -L docs; tests/docs/docs.cmake).

A command is a line of a fenced block (any language) that starts, after an optional `$ ` prompt
and `VAR=value` prefixes, with metrosync, build/metrosync, ./build/metrosync, metrosync-mpi,
metrosync_bench, mpirun, python3, bash or tools/...sh; continuation lines (a trailing backslash)
and heredocs (`<<'EOF'` .. `EOF`) belong to it, and the block's `NAME=value` lines and other
`$ ` lines before it run before it. The commands of one file run in order in one scratch folder, where `yaml`,
`tools` and `tests` are the source tree's, `build` the build tree and `docs` an empty folder (a
command's --out never writes into the source tree); the build tree is first on PATH and
PYTHONPATH. A command runs as shown, unless the table in tests/docs/shortenings.py shortens it
(and says how) or says why it cannot run. A `$ ` line followed by `metrosync: error: ...` lines is a
transcript: the command must exit 2 (or the table's code) and print those lines; `metrosync:
warning: ...` lines after it must be printed too (exit 0).

  run_docs.py commands FILE.md --source DIR --build DIR   run one file's commands
  run_docs.py table --source DIR                           every table entry still matches a command
  run_docs.py pointers --source DIR --build DIR            no user-facing text points outside
"""

import argparse
import glob
import os
import re
import resource
import shutil
import signal
import subprocess
import sys
import tempfile
import time

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import shortenings  # noqa: E402  (the table, beside this file)

COMMAND = re.compile(
    r"^(?:[A-Z_][A-Z0-9_]*=\S*\s+)*"  # VAR=value prefixes
    r"(?:\./)?(?:build/)?(?:metrosync(?:-mpi|_bench|_fit_bench)?|mpirun|python3|bash|"
    r"tools/\S+\.sh)(?=\s|$)")
ASSIGNMENT = re.compile(r"^[A-Za-z_][A-Za-z0-9_]*=")
SAID = re.compile(r"^metrosync: (error|warning): ")
HEREDOC = re.compile(r"<<-?\s*'?\"?([A-Za-z_]+)'?\"?")


class Command:
    def __init__(self, path, line, text, variables, transcript):
        self.path, self.line, self.text = path, line, text
        self.variables = list(variables)  # the block's NAME=value lines before it
        self.expected = []  # a transcript's "metrosync: error: ..." lines
        self.transcript = transcript

    def where(self):
        return "%s:%d" % (self.path, self.line)

    def first_line(self):
        """The first line, whitespace collapsed, without a trailing `# comment`."""
        line = re.sub(r"\s#\s.*$", "", self.text.split("\n", 1)[0])
        return " ".join(line.split())


def fenced_blocks(text):
    """(first line number, lines) of every fenced block."""
    lines = text.split("\n")
    i = 0
    while i < len(lines):
        m = re.match(r"^\s*(```+|~~~+)", lines[i])
        if not m:
            i += 1
            continue
        fence, start, body = m.group(1), i + 2, []
        i += 1
        while i < len(lines) and not lines[i].strip().startswith(fence):
            body.append(lines[i])
            i += 1
        i += 1
        yield start, body


def commands_of(path, source):
    """The commands of one Markdown file, in order."""
    rel = os.path.relpath(path, source)
    with open(path, encoding="utf-8") as f:
        text = f.read()
    found = []
    for start, body in fenced_blocks(text):
        variables, last, k = [], None, 0
        while k < len(body):
            raw = body[k].strip()
            line_no = start + k
            k += 1
            transcript = raw.startswith("$ ")
            line = raw[2:] if transcript else raw
            if last and last.transcript and SAID.match(raw):
                last.expected.append(raw)
                continue
            while line.endswith("\\") and k < len(body):  # continuation lines
                line = line[:-1].rstrip() + " " + body[k].strip()
                k += 1
            if not COMMAND.match(line):
                # NAME=value lines, and a transcript's other commands (`$ sed ... > bad.yaml`),
                # run before the block's later commands
                if transcript or ASSIGNMENT.match(line):
                    variables.append(line)
                last = None if raw == "" or transcript else last
                continue
            heredoc = HEREDOC.search(line)
            if heredoc:
                end, tail = heredoc.group(1), []
                while k < len(body) and body[k].strip() != end:
                    tail.append(body[k])
                    k += 1
                k += 1
                line = "\n".join([line] + tail + [end])
            last = Command(rel, line_no, line, variables, transcript)
            found.append(last)
    return found


def markdown_files(source):
    files = [os.path.join(source, "README.md")]
    files += sorted(glob.glob(os.path.join(source, "docs", "**", "*.md"), recursive=True))
    return files


def plan(cmd):
    """What the table says of `cmd`: (entry or None, the text to run or None, why)."""
    for entry in shortenings.TABLE:
        if entry.get("file") and entry["file"] != cmd.path:
            continue
        if not re.search(entry["match"], cmd.first_line()):
            continue
        if "skip" in entry:
            return entry, None, entry["skip"]
        text = cmd.text
        for pattern, replacement in entry.get("replace", []):
            text, n = re.subn(pattern, replacement, text)
            if n == 0:
                raise SystemExit("%s: the table's replacement %r matches nothing in %r" %
                                 (cmd.where(), pattern, cmd.first_line()))
        return entry, text, entry.get("why", "as shown")
    return None, cmd.text, "as shown"


def scratch(source, build):
    d = tempfile.mkdtemp(prefix="metrosync-docs-")
    for name in ("yaml", "tools", "tests"):
        os.symlink(os.path.join(source, name), os.path.join(d, name))
    os.symlink(build, os.path.join(d, "build"))
    os.mkdir(os.path.join(d, "docs"))
    return d


def environment(build):
    env = dict(os.environ)
    env["PATH"] = build + os.pathsep + env.get("PATH", "")
    env["PYTHONPATH"] = os.path.join(build, "python") + os.pathsep + env.get("PYTHONPATH", "")
    env.setdefault("OMPI_ALLOW_RUN_AS_ROOT", "1")
    env.setdefault("OMPI_ALLOW_RUN_AS_ROOT_CONFIRM", "1")
    return env


def run_file(md, source, build, timeout):
    cmds = commands_of(md, source)
    if not cmds:
        print("%s: no commands" % os.path.relpath(md, source))
        return 0
    folder, env, failures, t_all = scratch(source, build), environment(build), 0, time.time()
    # a command whose data a later block of the page makes runs after the page's others
    cmds = [c for c in cmds if not (plan(c)[0] or {}).get("defer")] + \
        [c for c in cmds if (plan(c)[0] or {}).get("defer")]
    try:
        for cmd in cmds:
            entry, text, why = plan(cmd)
            if text is None:
                print("NOT RUN  %s  %s\n         why: %s" % (cmd.where(), cmd.first_line(), why))
                continue
            errors = any(e.startswith("metrosync: error:") for e in cmd.expected)
            expect = (entry or {}).get("expect", 2 if errors else 0)
            script = "\n".join(cmd.variables + [(entry or {}).get("before", ""), text])
            t0, cpu0 = time.time(), resource.getrusage(resource.RUSAGE_CHILDREN)
            # its own process group: a command past its time is stopped with every child
            p = subprocess.Popen(["bash", "-c", script], cwd=folder, env=env,
                                 stdin=subprocess.DEVNULL, stdout=subprocess.PIPE,
                                 stderr=subprocess.PIPE, universal_newlines=True,
                                 start_new_session=True)
            try:
                out, err = p.communicate(timeout=timeout)
                code = p.returncode
            except subprocess.TimeoutExpired:
                os.killpg(p.pid, signal.SIGKILL)
                p.communicate()
                code, out, err = "timeout", "", "more than %d s: shorten it in %s" % (
                    timeout, "tests/docs/shortenings.py")
            dt, cpu1 = time.time() - t0, resource.getrusage(resource.RUSAGE_CHILDREN)
            cpu = cpu1.ru_utime + cpu1.ru_stime - cpu0.ru_utime - cpu0.ru_stime
            shown = "as shown" if text == cmd.text else "SHORTENED (%s): %s" % (
                why, " ".join(text.split("\n", 1)[0].split()))
            ok = code == expect and all(e in err for e in cmd.expected)
            print("%s  %s  %s\n         %s; exit %s (expected %s), %.1f s (%.1f s of CPU)" %
                  ("ok      " if ok else "FAILED  ", cmd.where(), cmd.first_line(), shown, code,
                   expect, dt, cpu))
            if not ok:
                failures += 1
                for e in cmd.expected:
                    if e not in err:
                        print("         expected on stderr: %s" % e)
                print("         stdout: %s\n         stderr: %s" % (out[-1500:], err[-1500:]))
    finally:
        shutil.rmtree(folder, ignore_errors=True)
    print("%s: %d commands, %d failed, %.1f s" % (os.path.relpath(md, source), len(cmds), failures,
                                                   time.time() - t_all))
    return 1 if failures else 0


def check_table(source):
    """Every table entry matches a command of the docs (a stale entry is an error)."""
    cmds = [c for md in markdown_files(source) for c in commands_of(md, source)]
    stale = 0
    for entry in shortenings.TABLE:
        hits = [c for c in cmds if (not entry.get("file") or entry["file"] == c.path)
                and re.search(entry["match"], c.first_line())]
        if not hits:
            stale += 1
            print("STALE  %r (%s) matches no command of README.md or docs/" %
                  (entry["match"], entry.get("file", "any file")))
    skipped = [(c, plan(c)[2]) for c in cmds if plan(c)[1] is None]
    print("%d commands in README.md and docs/, %d not run:" % (len(cmds), len(skipped)))
    for c, why in skipped:
        print("  %s  %s\n    why: %s" % (c.where(), c.first_line(), why))
    return 1 if stale else 0


# User-facing text must not point outside the repository: a clone has neither the contract's
# first form nor the paper's source.
OUTSIDE = re.compile(r"\.\./shared|SPEC\.md|\bSPEC (?:section )?\d|\(SPEC\b|\bthe SPEC\b|"
                     r"\bSPEC's\b|\bSPEC rules\b")


def check_pointers(source, build):
    texts = {}
    for md in markdown_files(source):
        with open(md, encoding="utf-8") as f:
            texts[os.path.relpath(md, source)] = f.read()
    for py in sorted(glob.glob(os.path.join(source, "tools", "python", "metrosync", "*.py*"))):
        with open(py, encoding="utf-8") as f:
            texts[os.path.relpath(py, source)] = f.read()
    # every --help, and every string literal of the C++ sources (help texts, messages)
    metrosync = os.path.join(build, "metrosync")
    commands = subprocess.run([metrosync, "--help"], stdout=subprocess.PIPE,
                              universal_newlines=True).stdout
    names = re.findall(r"^\s{2}([a-z][a-z-]+)\s", commands.split("SUBCOMMANDS:")[-1], re.M)
    if len(names) < 10:
        print("FAILED: metrosync --help lists %d commands: %s" % (len(names), names))
        return 1
    for name in [None] + names:
        args = [metrosync] + ([name] if name else []) + ["--help"]
        texts[" ".join(args[1:])] = subprocess.run(args, stdout=subprocess.PIPE,
                                                   universal_newlines=True).stdout
    for cpp in glob.glob(os.path.join(source, "*", "**", "*.cpp"), recursive=True):
        rel = os.path.relpath(cpp, source)
        if rel.startswith(("tests/", "build")):
            continue
        with open(cpp, encoding="utf-8") as f:
            literals = re.findall(r'"((?:[^"\\\n]|\\.)*)"', re.sub(r"//[^\n]*", "", f.read()))
        texts[rel + " (string literals)"] = "\n".join(literals)
    bad = 0
    for where, text in sorted(texts.items()):
        for m in OUTSIDE.finditer(text):
            line = text.count("\n", 0, m.start()) + 1
            bad += 1
            print("OUTSIDE  %s:%d: %r" % (where, line, text[max(0, m.start() - 40):m.end() + 40]))
    print("%d texts checked (README, docs/, the Python module, %d --help, C++ literals): %d "
          "pointers outside the repository" % (len(texts), len(names) + 1, bad))
    return 1 if bad else 0


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("mode", choices=["commands", "table", "pointers"])
    ap.add_argument("file", nargs="?")
    ap.add_argument("--source", required=True)
    ap.add_argument("--build")
    ap.add_argument("--timeout", type=int, default=150)
    a = ap.parse_args()
    source = os.path.abspath(a.source)
    if a.mode == "commands":
        return run_file(os.path.join(source, a.file), source, os.path.abspath(a.build), a.timeout)
    if a.mode == "table":
        return check_table(source)
    return check_pointers(source, os.path.abspath(a.build))


if __name__ == "__main__":
    sys.exit(main())
