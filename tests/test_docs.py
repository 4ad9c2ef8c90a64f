"""The README is for users first: under 300 lines, every page of docs/
reachable from it by a link, every relative link in the README and in
docs/ pointing at a file that exists, and every output file the writers name
(cracklip/io) named in the docs, so a user finds what a file holds; and every
```python block of the docs runs as written (convention below)."""
import re
import subprocess
import sys

import pytest

from conftest import ROOT

LINK = re.compile(r"\]\(([^)#\s]+)(?:#[^)]*)?\)")


def relative_links(path):
    return [m for m in LINK.findall(path.read_text()) if not re.match(r"[a-z]+://", m)]


def test_readme_is_short_and_links_every_page():
    readme = ROOT / "README.md"
    assert len(readme.read_text().splitlines()) < 300
    linked = {(readme.parent / link).resolve() for link in relative_links(readme)}
    pages = {p.resolve() for p in (ROOT / "docs").rglob("*.md")}
    assert pages, "docs/ has no pages"
    assert pages <= linked, f"pages not linked from the README: {sorted(str(p) for p in pages - linked)}"


def test_every_relative_link_resolves():
    for path in [ROOT / "README.md", *(ROOT / "docs").rglob("*.md")]:
        for link in relative_links(path):
            assert (path.parent / link).exists(), f"{path.relative_to(ROOT)} links to {link}, which does not exist"


OUTPUT_NAME = re.compile(r"[\"']([A-Za-z_]+\.(?:csv|png|txt|pvd|json|vtu))[\"']")


def test_every_output_file_is_documented():
    docs = " ".join(p.read_text() for p in [ROOT / "README.md", *(ROOT / "docs").rglob("*.md")])
    written = {(m, f.name) for f in (ROOT / "python" / "cracklip" / "io").glob("*.py")
               for m in OUTPUT_NAME.findall(f.read_text())}
    assert len(written) > 30, "the writers' file names were not found"
    missing = sorted(f"{name} ({writer})" for name, writer in written if name not in docs)
    assert not missing, f"output files the docs do not name: {missing}"


# The Python in the docs runs as written. Convention: every fenced ```python block of README.md
# and docs/**/*.md is a complete script, run on its own from the repository root (here a scratch
# directory whose demos/ is the repository's, so output files stay out of the repository); a
# block whose first line is "# not run: <why>" (e.g. a mesh too large for the test suite) is
# skipped. Untagged ``` blocks and ```toml / ```sh blocks are not Python and are not run.
PYTHON_BLOCK = re.compile(r"^```python\n(.*?)^```", re.S | re.M)
NOT_RUN = "# not run:"


def python_blocks():
    for path in [ROOT / "README.md", *sorted((ROOT / "docs").rglob("*.md"))]:
        text = path.read_text()
        for m in PYTHON_BLOCK.finditer(text):
            line = text.count("\n", 0, m.start()) + 1
            yield pytest.param(m.group(1), id=f"{path.relative_to(ROOT)}:{line}")


def test_docs_have_python_blocks():
    assert len(list(python_blocks())) >= 2, "the README's and docs/life.md's Python examples were not found"


@pytest.mark.parametrize("code", python_blocks())
def test_python_block_runs_as_written(code, tmp_path):
    if code.lstrip().startswith(NOT_RUN):
        pytest.skip(code.lstrip().splitlines()[0])
    (tmp_path / "demos").symlink_to(ROOT / "demos")
    (tmp_path / "block.py").write_text(code)
    env = {"PYTHONPATH": str(ROOT / "python"), "MPLBACKEND": "Agg", "PATH": "/usr/bin:/bin",
           "GLIBC_TUNABLES": "glibc.malloc.hugetlb=1"}
    run = subprocess.run([sys.executable, "block.py"], cwd=tmp_path, env=env, capture_output=True,
                         text=True, timeout=600)
    assert run.returncode == 0, f"the block fails:\n{code}\n{run.stderr[-3000:]}"
