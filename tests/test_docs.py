"""The README is for users first: under 300 lines, every page of docs/
reachable from it by a link, every relative link in the README and in
docs/ pointing at a file that exists, and every output file the writers name
(cracklip/io) named in the docs, so a user finds what a file holds."""
import re

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
