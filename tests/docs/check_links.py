#!/usr/bin/python3
"""Every relative link of the repository's Markdown pages resolves: the file or folder exists
and, for a link into a Markdown page, the #anchor is one of its headings as GitHub names them.

  /usr/bin/python3 tests/docs/check_links.py [ROOT]

Prints each broken link as FILE:LINE: TARGET (reason) and exits 1 if there is one.
"""
import pathlib
import re
import subprocess
import sys
import unicodedata

LINK = re.compile(r"!?\[(?:[^\]\[]|\[[^\]]*\])*\]\(([^)\s]+)(?:\s+\"[^\"]*\")?\)")
HEADING = re.compile(r"^(#{1,6})\s+(.*?)\s*#*\s*$")
FENCE = re.compile(r"^\s*(```|~~~)")


def prose_lines(text, blank_code=True):
    """(line number, line) outside fenced code blocks, with code spans blanked unless asked not to
    (a link's brackets inside a code span are not a link; a heading's code is part of its name)."""
    fenced = False
    for number, line in enumerate(text.split("\n"), 1):
        if FENCE.match(line):
            fenced = not fenced
            continue
        if not fenced:
            yield number, re.sub(r"`[^`]*`", lambda m: "`" + "x" * (len(m.group(0)) - 2) + "`", line) if blank_code else line


def github_anchor(heading):
    """The id GitHub gives a heading: lower case, punctuation dropped, spaces as hyphens."""
    text = re.sub(r"!?\[([^\]]*)\]\([^)]*\)", r"\1", heading)  # a link's text
    text = text.replace("`", "").lower()
    kept = "".join(c for c in text if c in " -_" or unicodedata.category(c)[0] in "LN")
    return kept.replace(" ", "-")


def anchors(path):
    seen = {}
    result = set()
    for _, line in prose_lines(path.read_text(encoding="utf-8"), blank_code=False):
        match = HEADING.match(line)
        if not match:
            continue
        base = github_anchor(match.group(2))
        count = seen.get(base, 0)
        seen[base] = count + 1
        result.add(base if count == 0 else f"{base}-{count}")
    return result


def markdown_files(root):
    listed = subprocess.run(["git", "-C", str(root), "ls-files", "--cached", "--others", "--exclude-standard", "*.md"], capture_output=True, text=True)
    if listed.returncode == 0 and listed.stdout.strip():
        names = listed.stdout.split()
    else:  # not a git checkout: every page outside build folders and node_modules
        names = [str(p.relative_to(root)) for p in root.rglob("*.md")]
    skip = ("node_modules/", "build", "tests/golden/")
    return [root / n for n in names if not n.startswith(skip) and "/node_modules/" not in n]


def broken_links(root):
    cache = {}
    for page in markdown_files(root):
        for number, line in prose_lines(page.read_text(encoding="utf-8")):
            for match in LINK.finditer(line):
                target = match.group(1)
                if re.match(r"^[a-z][a-z0-9+.-]*:", target):  # http:, https:, mailto:
                    continue
                path_part, _, anchor = target.partition("#")
                where = (page.parent / path_part).resolve() if path_part else page
                if not where.exists():
                    yield page, number, target, "no such file"
                    continue
                if anchor and where.suffix == ".md":
                    if where not in cache:
                        cache[where] = anchors(where)
                    if anchor not in cache[where]:
                        yield page, number, target, "no such heading"


def main():
    root = pathlib.Path(sys.argv[1] if len(sys.argv) > 1 else pathlib.Path(__file__).resolve().parents[2])
    broken = list(broken_links(root))
    for page, number, target, reason in broken:
        print(f"{page.relative_to(root)}:{number}: {target} ({reason})")
    pages = len(markdown_files(root))
    print(f"{pages} pages, {len(broken)} broken links")
    return 1 if broken else 0


if __name__ == "__main__":
    sys.exit(main())
