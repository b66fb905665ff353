"""The README as a front page, and the links of the documentation.

- README.md has at most 160 lines and no line of its tables is longer than 200 characters;
- it carries no measured figure (MHz, LUTs, logic levels, match rates, ...): those are
  generated into docs/results.md by `make synth` and `make bench`, and the README links there;
- every relative link of README.md and docs/**/*.md names a file or folder that exists, and
  its `#anchor`, if any, a heading of that page (GitHub's rule) or an explicit HTML anchor.
"""

from __future__ import annotations

import re
from pathlib import Path
from urllib.parse import unquote

import pytest

REPO = Path(__file__).resolve().parents[2]
README = REPO / "README.md"
PAGES = [README, *sorted((REPO / "docs").rglob("*.md"))]

MAX_LINES = 160
MAX_TABLE_LINE = 200

# A measured figure: a number with a unit of resources, clock, time or rate after it, or a
# resource name with a number after it. Sizes (1920x1080), versions (0.2.0, 4.14.0),
# widths (64-bit) and counts of things (6 beats, 4 per cell, every 64 clocks) are not.
NUMBER = r"(?<![\w.])\d+(?:[ ,\u00a0\u202f]\d{3})*(?:\.\d+)?(?![\w.])"
UNIT = (
    r"(?:[kMG]Hz|LUTs?|FFs?|BRAM(?:18|36)?s?|RAMB(?:18|36)s?|DSP(?:48E?1?)?s?|SRLs?"
    r"|CARRY4s?|DP16KDs?|Mpixels?/s|fps|%|ms|s|min|minutes|seconds?|(?:logic )?levels?"
    r"|(?:clocks?|cycles?) per pixel|matches)"
)
FIGURE = re.compile(
    rf"{NUMBER}\s?{UNIT}(?![\w/])|\b(?:LUTs?|FFs?|BRAM18|DSP48|Fmax|WNS)\s*[:=]?\s*\d"
)

FENCE = re.compile(r"^(```|~~~).*?^\1[^\n]*$", re.S | re.M)
CODE_SPAN = re.compile(r"(`+)(?!`).*?(?<!`)\1(?!`)", re.S)
INLINE_LINK = re.compile(r"!?\[(?:[^\[\]]|\[[^\]]*\])*\]\(\s*<?([^)\s>]+)>?(?:\s+\"[^\"]*\")?\s*\)")
REFERENCE = re.compile(r"^\s{0,3}\[[^\]]+\]:\s*<?(\S+?)>?(?:\s|$)", re.M)
HTML_LINK = re.compile(r"<(?:a|img)\b[^>]*?\b(?:href|src)\s*=\s*[\"']([^\"']+)[\"']", re.I)
HTML_ANCHOR = re.compile(r"<a\b[^>]*?\b(?:id|name)\s*=\s*[\"']([^\"']+)[\"']", re.I)
HEADING = re.compile(r"^ {0,3}#{1,6}[ \t]+(.+?)[ \t]*#*[ \t]*$", re.M)
SCHEME = re.compile(r"^[a-zA-Z][a-zA-Z0-9+.-]*:")


def without_code(text: str) -> str:
    """The text without fenced blocks and code spans (their brackets are not links)."""
    return CODE_SPAN.sub("", FENCE.sub("", text))


def slug(heading: str) -> str:
    """GitHub's anchor of a heading: its text (code marks, emphasis, links and HTML
    dropped), lowercased, punctuation other than `-` and `_` dropped, spaces to `-`."""
    text = re.sub(r"!?\[([^\]]*)\]\([^)]*\)", r"\1", heading)
    text = re.sub(r"<[^>]+>", "", text).replace("`", "").replace("*", "")
    text = re.sub(r"[^\w\- ]", "", text.strip().lower())
    return text.replace(" ", "-")


def anchors(page: Path) -> set[str]:
    """The anchors of a page: one per heading (repeats numbered -1, -2, ... as GitHub
    does) and its explicit `<a id=...>` / `<a name=...>` anchors."""
    text = FENCE.sub("", page.read_text())
    found: set[str] = set()
    seen: dict[str, int] = {}
    for m in HEADING.finditer(text):
        base = slug(m.group(1))
        n = seen.get(base, 0)
        seen[base] = n + 1
        found.add(base if n == 0 else f"{base}-{n}")
    found |= set(HTML_ANCHOR.findall(text))
    return found


def links(page: Path) -> list[str]:
    text = without_code(page.read_text())
    return [
        *INLINE_LINK.findall(text),
        *REFERENCE.findall(text),
        *HTML_LINK.findall(text),
    ]


def broken_links(page: Path) -> list[str]:
    """The relative links of a page that name no file, or no anchor of their page."""
    broken = []
    for link in links(page):
        if SCHEME.match(link):  # https:, mailto:, ...: not checked here
            continue
        path, _, anchor = link.partition("#")
        path = unquote(path)
        if path:
            target = (REPO / path.lstrip("/")) if path.startswith("/") else page.parent / path
        else:
            target = page
        if not target.exists():
            broken.append(f"{link} (no such file)")
        elif anchor and target.suffix == ".md" and unquote(anchor) not in anchors(target):
            broken.append(f"{link} (no heading with that anchor)")
    return broken


def figures(text: str) -> list[str]:
    return [m.group(0) for m in FIGURE.finditer(text)]


def test_readme_is_short() -> None:
    lines = README.read_text().splitlines()
    assert len(lines) <= MAX_LINES, (
        f"README.md has {len(lines)} lines (at most {MAX_LINES}): move the detail to docs/"
    )


def test_readme_tables_have_short_lines() -> None:
    long = [
        f"line {i}: {len(line)} characters"
        for i, line in enumerate(README.read_text().splitlines(), 1)
        if line.lstrip().startswith("|") and len(line) > MAX_TABLE_LINE
    ]
    assert not long, f"README.md table lines over {MAX_TABLE_LINE} characters: {long}"


def test_readme_has_no_measured_figure() -> None:
    found = figures(README.read_text())
    assert not found, (
        f"README.md: measured figures written by hand {found}; link docs/results.md instead"
    )


@pytest.mark.parametrize(
    "text",
    [
        "158 MHz",
        "142.857 MHz",
        "2553 LUT",
        "23 641 LUTs",
        "LUT 2553",
        "12 BRAM18",
        "21 DSP48E1",
        "87.9 % correct",
        "87.9% correct",
        "356 matches",
        "1.00062 clocks per pixel",
        "about 2 s of simulation",
        "in 9 min",
        "4 logic levels",
        "Fmax 158",
        "124.4 Mpixel/s",
    ],
)
def test_figure_pattern_finds_figures(text: str) -> None:
    assert figures(f"the top: {text}, as measured"), text


@pytest.mark.parametrize(
    "text",
    [
        "1920x1080 and 3840x2160",
        "a 7x7 window",
        "version 0.2.0, the IP 0.2",
        "OpenCV 4.14.0 (opencv-python-headless==4.14.0.94)",
        "Python >= 3.11, GHDL >= 2.0, Vivado 2020.2",
        "64-bit records, a 12-bit address",
        "xc7z020clg484-1, AXI4-Lite, FAST-9/16, UG934",
        "6 beats per keypoint, at most 4 per 64x64 cell, a keypoint every 64 clocks",
        "1, 2 or 4 pixels per clock; K 1 .. 15",
        "DSP48E1 and LUT RAM",
    ],
)
def test_figure_pattern_allows_sizes_and_versions(text: str) -> None:
    assert not figures(text), figures(text)


def test_slug_follows_github() -> None:
    assert slug("fastnms_axil_slave (internal)") == "fastnms_axil_slave-internal"
    assert slug("Video in: `s_axis_video` (AXI4-Stream video, AMD UG934)") == (
        "video-in-s_axis_video-axi4-stream-video-amd-ug934"
    )
    assert slug("The blur (`fastnms_orb_blur`)") == "the-blur-fastnms_orb_blur"
    assert slug("Record format 2 (ORB)") == "record-format-2-orb"


@pytest.mark.parametrize("page", PAGES, ids=lambda p: str(p.relative_to(REPO)))
def test_relative_links_resolve(page: Path) -> None:
    broken = broken_links(page)
    assert not broken, f"{page.relative_to(REPO)}: broken links {broken}"
