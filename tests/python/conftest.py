"""Shared by the tests of the Python module: where the sources and the CLI are (ctest sets
METROSYNC_SOURCE_DIR and METROSYNC_BINARY), the shipped rigs, and the CLI's number formats."""
import csv
import os
import subprocess

import pytest
import yaml

SRC = os.path.abspath(os.environ["METROSYNC_SOURCE_DIR"])
BIN = os.path.abspath(os.environ["METROSYNC_BINARY"])
RIGS = os.path.join(SRC, "yaml", "rigs")
EXPERIMENT = os.path.join(RIGS, "experiment.yaml")
MAP_RIG = os.path.join(RIGS, "experiment-map.yaml")
F44 = os.path.join(RIGS, "paper", "f4.4-alpha4.yaml")


def cli(*args):
    """Runs the command-line program; its stdout (it must succeed)."""
    return subprocess.run([BIN, *args], check=True, capture_output=True, text=True).stdout


def rig_dict(path):
    """A shipped rig as the dict a user would write (the YAML's structure)."""
    with open(path, encoding="utf-8") as f:
        return yaml.safe_load(f)


def read_rows(path):
    with open(path, newline="", encoding="utf-8") as f:
        rows = list(csv.reader(f))
    return rows[0], rows[1:]


def printed(name, value, tau_digits=10):
    """A number as the CLI's CSV files print it: %.12g; the tau column of an envelope, sweep or
    comparison %.10g (sim/record/envelope.cpp, tools/report/outputs.cpp)."""
    return ("%%.%dg" % (tau_digits if name == "tau" else 12)) % value


def assert_columns_print_as(columns, path, text_columns=(), tau_digits=10, near=()):
    """The file at `path` is, line for line, the columns printed the CLI's way: the arrays are
    the numbers the CLI printed. Columns in `near` only to 1e-9 (see the caller)."""
    header, rows = read_rows(path)
    assert list(columns) == header
    assert len(rows) > 0
    for name in header:
        assert len(columns[name]) == len(rows), name
    for i, row in enumerate(rows):
        for k, name in enumerate(header):
            value = columns[name][i]
            if name in near:
                assert abs(value - float(row[k])) <= 1e-9 * abs(value), (path, i, name)
                continue
            shown = str(value) if name in text_columns else printed(name, value, tau_digits)
            assert shown == row[k], (path, i, name, value, row[k])


@pytest.fixture
def no_temporary_folder(monkeypatch, tmp_path):
    """Fails a test whose call makes a temporary folder or writes into the working folder."""
    import tempfile

    def refuse(*args, **kwargs):
        raise AssertionError("a temporary folder was made")

    monkeypatch.setattr(tempfile, "mkdtemp", refuse)
    monkeypatch.setattr(tempfile, "TemporaryDirectory", refuse)
    work = tmp_path / "work"
    work.mkdir()
    monkeypatch.chdir(work)
    yield work
    assert list(work.iterdir()) == [], "files were written"
