"""The command line on glibc's huge pages (solvers/huge_pages.py): when it
restarts itself with GLIBC_TUNABLES=glibc.malloc.hugetlb=1, and that the
restarted run says so in results.json (or not, with CRACKLIP_HUGE_PAGES=0)."""
from __future__ import annotations

import json
import subprocess
import sys

import pytest
from conftest import ROOT

from cracklip.solvers.huge_pages import (glibc_version, in_use, pages, restart_wanted, started_as_module,
                                         thp_mode, with_tunable)

BLOCK = ROOT / "demos" / "scenes" / "block_uniform_pressure.toml"
ENV = {"PYTHONPATH": str(ROOT / "python"), "PATH": "/usr/bin:/bin", "MPLBACKEND": "Agg"}


def test_restart_only_where_it_helps_and_once():
    on = "glibc.malloc.hugetlb=1"
    assert restart_wanted({}, "madvise", (2, 36))
    assert not restart_wanted({}, "always", (2, 36))  # (malloc's memory is on huge pages anyway)
    assert not restart_wanted({}, "never", (2, 36))
    assert not restart_wanted({}, "", (2, 36))
    assert not restart_wanted({}, "madvise", (2, 34))  # (glibc before the tunable)
    assert not restart_wanted({}, "madvise", None)     # (musl and others)
    assert not restart_wanted({"GLIBC_TUNABLES": on}, "madvise", (2, 36))  # (the restarted process)
    assert not restart_wanted({"GLIBC_TUNABLES": f"glibc.malloc.arena_max=2:{on}"}, "madvise", (2, 36))
    assert not restart_wanted({"CRACKLIP_HUGE_PAGES": "0"}, "madvise", (2, 36))
    assert restart_wanted({"CRACKLIP_HUGE_PAGES": "1"}, "madvise", (2, 36))


def test_tunable_added_to_the_others():
    assert with_tunable({})["GLIBC_TUNABLES"] == "glibc.malloc.hugetlb=1"
    env = with_tunable({"GLIBC_TUNABLES": "glibc.malloc.arena_max=2", "X": "1"})
    assert env == {"GLIBC_TUNABLES": "glibc.malloc.arena_max=2:glibc.malloc.hugetlb=1", "X": "1"}
    assert in_use(env) and not in_use({"GLIBC_TUNABLES": "glibc.malloc.hugetlb=0"})


def test_pages_named_by_what_gives_them():
    on = {"GLIBC_TUNABLES": "glibc.malloc.hugetlb=1"}
    assert pages(on, "madvise") == "huge pages (GLIBC_TUNABLES)"
    assert pages({}, "madvise") == "default pages"
    assert pages(on, "never") == "default pages"  # (the tunable asks, the kernel gives none)
    assert pages({}, "always") == "huge pages (kernel THP always)"


def test_thp_mode_reads_the_bracketed_word(tmp_path):
    f = tmp_path / "enabled"
    f.write_text("always [madvise] never\n")
    assert thp_mode(str(f)) == "madvise"
    f.write_text("[always] madvise never\n")
    assert thp_mode(str(f)) == "always"
    assert thp_mode(str(tmp_path / "missing")) == ""


def test_only_the_module_command_line_restarts():
    py = "/usr/bin/python3"
    assert started_as_module([py, "-m", "cracklip", "run", "x.toml"])
    assert started_as_module([py, "-X", "dev", "-u", "-m", "cracklip"])
    assert not started_as_module([py, "-m", "pytest"])
    assert not started_as_module([py, "-c", "import runpy; runpy.run_module('cracklip')"])  # (a wrapper)
    assert not started_as_module([py, "script.py", "-m", "cracklip"])
    assert not started_as_module([])


@pytest.mark.parametrize("opt_out", [False, True])
def test_cli_run_records_its_pages(tmp_path, opt_out):
    env = {**ENV, "CRACKLIP_HUGE_PAGES": "0"} if opt_out else ENV
    p = subprocess.run([sys.executable, "-m", "cracklip", "run", str(BLOCK), "--out", str(tmp_path), "--quiet"],
                       cwd=ROOT, env=env, capture_output=True, text=True, timeout=300)
    assert p.returncode == 0, p.stderr
    malloc = json.loads((tmp_path / "results.json").read_text())["versions"]["malloc"]
    mode = thp_mode()
    huge = restart_wanted(env, mode, glibc_version())
    assert malloc == ("huge pages (GLIBC_TUNABLES)" if huge else
                      "huge pages (kernel THP always)" if mode == "always" else "default pages")
    if opt_out:
        assert malloc != "huge pages (GLIBC_TUNABLES)"
