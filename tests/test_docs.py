"""The README is for users first: under 300 lines, every page of docs/
reachable from it by a link, every relative link in the README and in
docs/ pointing at a file that exists."""
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
