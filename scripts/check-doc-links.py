#!/usr/bin/python3
"""Check the relative links of the project's Markdown pages: the file each one names exists,
and the heading its #anchor names is in it (anchors as GitHub makes them from headings).

Usage: check-doc-links.py [ROOT]   (ROOT: the project's source folder; default: this script's
parent folder). Checks ROOT/README.md and ROOT/docs/*.md. Exit 0 when every link resolves, 1
with one line per broken link (file:line: link: why), 2 on bad usage.
"""
import functools
import re
import sys
from pathlib import Path

# [text](target) and [text](target "title"); images too. Not inside inline code.
LINK = re.compile(r"!?\[[^\]]*\]\(([^)\s]+)(?:\s+\"[^\"]*\")?\)")
HEADING = re.compile(r"^(#{1,6})\s+(.*?)\s*#*\s*$")
FENCE = re.compile(r"^\s*(```|~~~)")
INLINE_CODE = re.compile(r"`[^`]*`")


def slug(heading):
    """GitHub's anchor for a heading: lower case, Markdown link syntax and punctuation dropped
    (letters, digits, spaces, hyphens and underscores kept), spaces to hyphens."""
    text = re.sub(r"\[([^\]]*)\]\([^)]*\)", r"\1", heading)  # a link keeps its text
    text = text.replace("`", "").lower()
    text = "".join(c for c in text if c.isalnum() or c in " -_")
    return text.replace(" ", "-")


def lines_outside_fences(path):
    """(line number, line) of a Markdown file, code blocks left out."""
    inside = False
    for number, line in enumerate(path.read_text(encoding="utf-8").splitlines(), 1):
        if FENCE.match(line):
            inside = not inside
            continue
        if not inside:
            yield number, line


@functools.lru_cache(maxsize=None)
def anchors(path):
    """The anchors of a Markdown file's headings; a repeated heading gets -1, -2... as on
    GitHub, and HTML anchors (<a name="..."> or id="...") count too."""
    found, seen = set(), {}
    for _, line in lines_outside_fences(path):
        match = HEADING.match(line)
        if match:
            base = slug(match.group(2))
            count = seen.get(base, 0)
            seen[base] = count + 1
            found.add(base if count == 0 else f"{base}-{count}")
        found.update(re.findall(r"<a\s+(?:name|id)=\"([^\"]+)\"", line))
    return found


def broken_links(page):
    """(line, link, why) for each relative link of `page` that does not resolve."""
    for number, line in lines_outside_fences(page):
        for target in LINK.findall(INLINE_CODE.sub("", line)):
            if re.match(r"^[a-z][a-z0-9+.-]*:", target):  # http:, https:, mailto:...
                continue
            file_part, _, anchor = target.partition("#")
            linked = (page.parent / file_part).resolve() if file_part else page
            if not linked.exists():
                yield number, target, f"no file {linked}"
            elif anchor and linked.suffix == ".md" and anchor not in anchors(linked):
                yield number, target, f"no heading with anchor #{anchor} in {linked.name}"


def main(argv):
    if len(argv) > 2 or (len(argv) == 2 and argv[1] in ("-h", "--help")):
        print(__doc__.strip())
        return 0 if len(argv) == 2 and argv[1] in ("-h", "--help") else 2
    root = Path(argv[1]) if len(argv) == 2 else Path(__file__).resolve().parent.parent
    pages = [root / "README.md"] + sorted((root / "docs").glob("*.md"))
    missing = [page for page in pages if not page.exists()]
    if missing:
        print(f"check-doc-links: no such page: {missing[0]}", file=sys.stderr)
        return 2
    broken = 0
    for page in pages:
        for number, target, why in broken_links(page):
            print(f"{page.relative_to(root)}:{number}: ({target}): {why}")
            broken += 1
    print(f"check-doc-links: {len(pages)} pages, {broken} broken link(s)")
    return 1 if broken else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
