"""The Python examples of the README and of the user guide (docs/src), run as written.

Every ```python block is run on its own, from a scratch directory where `tests/` leads
to the repository's, so the examples' paths (`tests/data/spot.obj`) are the
repository's and what they write stays out of the clone. A block whose first line is
`# requires: a, b` runs only where each item is there: an item with a `/` or a `.` is
a file of the repository (a DEM that is not bundled, say), any other a module to
import (dask on a Python without the extra). Keep such blocks rare: a skipped example
is an untested one.
"""

import importlib.util
import os
import re
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[2]
GUIDE = ROOT / "docs" / "src"
PAGES = [ROOT / "README.md"] + sorted(p for p in GUIDE.glob("*.md") if p.name != "SUMMARY.md")
BLOCK = re.compile(r"^```python\n(.*?)^```$", re.M | re.S)
REQUIRES = re.compile(r"#\s*requires:\s*(.*)")


def python_blocks():
    """(id, code) for every ```python block, the id naming its page and line."""
    blocks = []
    for page in PAGES:
        text = page.read_text(encoding="utf-8")
        for match in BLOCK.finditer(text):
            line = text.count("\n", 0, match.start()) + 1
            blocks.append((f"{page.relative_to(ROOT).as_posix()}:{line}", match.group(1)))
    return blocks


BLOCKS = python_blocks()


def missing_requirements(code):
    """What a block's `# requires:` line names that is not here (nothing if no line)."""
    first = code.split("\n", 1)[0]
    found = REQUIRES.fullmatch(first.strip())
    if not found:
        return []
    missing = []
    for item in (i.strip() for i in found.group(1).split(",")):
        if not item:
            continue
        if "/" in item or "." in item:
            if not (ROOT / item).exists():
                missing.append(item)
        elif importlib.util.find_spec(item) is None:
            missing.append(item)
    return missing


def test_the_readme_and_the_guide_have_python_examples():
    # Guards the extraction itself: a pattern that found nothing would pass every
    # parametrized case below by having none.
    pages = {block_id.split(":")[0] for block_id, _ in BLOCKS}
    assert "README.md" in pages and "docs/src/python.md" in pages, sorted(pages)


@pytest.mark.parametrize("block_id, code", BLOCKS, ids=[i for i, _ in BLOCKS])
def test_the_example_runs(block_id, code, tmp_path, monkeypatch):
    missing = missing_requirements(code)
    if missing:
        pytest.skip(f"needs {', '.join(missing)}")
    os.symlink(ROOT / "tests", tmp_path / "tests", target_is_directory=True)
    monkeypatch.chdir(tmp_path)
    # Tracebacks name the page and the block's line in it.
    exec(compile(code, block_id, "exec"), {"__name__": "__example__"})


def test_every_guide_page_is_in_the_book_and_compiled():
    # A page left out of SUMMARY.md is not in the book; one left out of src/lib.rs's
    # `guide` module (or, for the Terrain page, whose code needs the terrain crate,
    # terrain/src/lib.rs's) has its Rust examples never compiled.
    summary = (GUIDE / "SUMMARY.md").read_text(encoding="utf-8")
    lib = (ROOT / "src" / "lib.rs").read_text(encoding="utf-8")
    terrain_lib = (ROOT / "terrain" / "src" / "lib.rs").read_text(encoding="utf-8")
    for page in PAGES[1:]:
        assert f"]({page.name})" in summary, f"{page.name} is not in SUMMARY.md"
        compiled = f'include_str!("../docs/src/{page.name}")' in lib or (
            f'include_str!("../../docs/src/{page.name}")' in terrain_lib
        )
        assert compiled, f"{page.name} is in neither src/lib.rs nor terrain/src/lib.rs"


LINK = re.compile(r"\]\(([^)\s]+)\)")
HEADING = re.compile(r"^#{1,6} (.+)$", re.M)
FENCE = re.compile(r"^```.*?^```$", re.M | re.S)


def anchors(page):
    """The anchors of a page's headings, as mdBook and GitHub make them."""
    text = FENCE.sub("", page.read_text(encoding="utf-8"))
    found = set()
    for heading in HEADING.findall(text):
        slug = re.sub(r"[^\w\- ]", "", heading.strip().lower()).replace(" ", "-")
        found.add(slug)
    return found


def test_links_between_pages_lead_somewhere():
    # mdBook does not check links: a renamed page or heading would leave readers of
    # the README and of the guide at a dead end.
    broken = []
    for page in PAGES:
        text = FENCE.sub("", page.read_text(encoding="utf-8"))
        for target in LINK.findall(text):
            if re.match(r"[a-z]+:", target):
                continue  # https:, mailto:
            path, _, anchor = target.partition("#")
            goal = (page.parent / path).resolve() if path else page
            if not goal.exists():
                broken.append(f"{page.name}: {target} (no such file)")
            elif anchor and goal.suffix == ".md" and anchor not in anchors(goal):
                broken.append(f"{page.name}: {target} (no such heading)")
    assert not broken, "\n".join(broken)
