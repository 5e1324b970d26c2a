#!/usr/bin/env python3
"""ctest docs.links: every relative link of the manual leads somewhere.

The manual is spread over Markdown files beside the code (README.md, src/**/README.md, the user
guide, the report schemas, tests/**/README.md). A file renamed or a heading reworded would leave
links that lead nowhere; this check follows every relative link of every tracked .md file: the
file or folder must exist and, for a link into a Markdown file with #anchor, the anchor must be a
heading of that file (GitHub's rule: lower case, punctuation dropped, spaces to hyphens).

Usage: check_links.py SOURCE_DIR
"""
import os
import re
import subprocess
import sys

LINK = re.compile(r"\[[^\]]*\]\(([^)\s]+)\)")
HEADING = re.compile(r"^#{1,6}\s+(.*?)\s*#*\s*$")
FENCE = re.compile(r"^\s*(```|~~~)")


def markdown_files(root):
    out = subprocess.run(["git", "-C", root, "ls-files", "*.md"], capture_output=True, text=True)
    if out.returncode == 0 and out.stdout.strip():
        return out.stdout.split()
    # Not a git checkout (a source tarball): every .md file outside build folders.
    found = []
    for folder, dirs, files in os.walk(root):
        dirs[:] = [d for d in dirs if not d.startswith((".", "build"))]
        found += [os.path.relpath(os.path.join(folder, f), root) for f in files if f.endswith(".md")]
    return found


def lines_outside_code(text):
    fenced = False
    for line in text.splitlines():
        if FENCE.match(line):
            fenced = not fenced
            continue
        if not fenced:
            yield line


def slug(heading):
    text = re.sub(r"`|\*\*|\*", "", heading).strip().lower()
    text = re.sub(r"\[([^\]]*)\]\([^)]*\)", r"\1", text)  # a link in a heading: its text
    text = re.sub(r"[^\w\- ]", "", text)
    return text.replace(" ", "-")


def anchors(path, cache={}):
    if path not in cache:
        seen = {}
        result = set()
        with open(path, encoding="utf-8") as f:
            for line in lines_outside_code(f.read()):
                m = HEADING.match(line)
                if not m:
                    continue
                base = slug(m.group(1))
                n = seen.get(base, 0)
                seen[base] = n + 1
                result.add(base if n == 0 else f"{base}-{n}")
        cache[path] = result
    return cache[path]


def main():
    if len(sys.argv) != 2:
        sys.exit("usage: check_links.py SOURCE_DIR")
    root = sys.argv[1]
    problems = []
    files = markdown_files(root)
    links = 0
    for rel in files:
        path = os.path.join(root, rel)
        with open(path, encoding="utf-8") as f:
            text = f.read()
        fenced = False
        for number, line in enumerate(text.splitlines(), 1):
            if FENCE.match(line):
                fenced = not fenced
            if fenced:
                continue
            for target in LINK.findall(line):
                if re.match(r"^[a-z][a-z0-9+.-]*:", target):  # http:, mailto: ...
                    continue
                links += 1
                file_part, _, anchor = target.partition("#")
                dest = os.path.normpath(os.path.join(os.path.dirname(path), file_part)) \
                    if file_part else path
                if not os.path.exists(dest):
                    problems.append(f"{rel}:{number}: link '{target}': no file {file_part}")
                elif anchor and dest.endswith(".md") and anchor not in anchors(dest):
                    problems.append(f"{rel}:{number}: link '{target}': no heading #{anchor} "
                                    f"in {os.path.relpath(dest, root)}")
    for p in problems:
        print(p)
    if problems:
        print(f"FAIL: {len(problems)} broken links")
        return 1
    print(f"PASS: {links} relative links in {len(files)} Markdown files lead somewhere")
    return 0


if __name__ == "__main__":
    sys.exit(main())
