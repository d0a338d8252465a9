#!/usr/bin/env python3
"""Fails when src/, include/, docs/ or README.md read like a lab journal: a commit hash, or the
words "session" or "sitting" (measurements and stories belong in commit messages).

usage: check_journal.py [--junit DIR] [ROOT]   (ROOT: the repository, default this script's ../)
Prints one line per hit (path:line: token) and exits 1 when there is any; with --junit it also
writes DIR/journal.xml, one test case per checked folder or file, for make test's count.
"""
import os
import re
import sys
from xml.sax.saxutils import escape, quoteattr

CHECKED = ["src", "include", "docs", "README.md"]
# A whole word of 7-40 hex digits with at least one letter and one digit: a commit hash, not a
# number (1048576), not a hex literal (0x1f is one word with an x), not an English word.
HASH = re.compile(r"(?<![\w-])(?=[0-9a-fA-F]*[a-fA-F])(?=[0-9a-fA-F]*[0-9])[0-9a-fA-F]{7,40}(?![\w-])")
WORDS = re.compile(r"\b(sessions?|sittings?)\b", re.IGNORECASE)


def hits(path):
    """(line number, token) for every hit in one text file; binary files have none."""
    with open(path, "rb") as f:
        data = f.read()
    if b"\0" in data:
        return []
    out = []
    for n, line in enumerate(data.decode("utf-8", "replace").splitlines(), 1):
        out += [(n, m.group(0)) for m in HASH.finditer(line)]
        out += [(n, m.group(0)) for m in WORDS.finditer(line)]
    return out


def files(root, entry):
    path = os.path.join(root, entry)
    if os.path.isfile(path):
        return [path]
    return sorted(os.path.join(d, f) for d, _, fs in os.walk(path) for f in fs)


def main(argv):
    junit = None
    if argv[:1] == ["--junit"]:
        junit, argv = argv[1], argv[2:]
    root = argv[0] if argv else os.path.join(os.path.dirname(os.path.abspath(__file__)), "..")
    cases = []  # (name, [hit lines])
    for entry in CHECKED:
        lines = [f"{os.path.relpath(p, root)}:{n}: {tok}"
                 for p in files(root, entry) for n, tok in hits(p)]
        cases.append((entry, lines))
        for line in lines:
            print(line)
    failed = sum(1 for _, lines in cases if lines)
    if junit:
        os.makedirs(junit, exist_ok=True)
        with open(os.path.join(junit, "journal.xml"), "w") as f:
            f.write(f'<testsuite name="journal" tests="{len(cases)}" failures="{failed}" errors="0" skipped="0">\n')
            for name, lines in cases:
                f.write(f'  <testcase classname="journal" name={quoteattr(name)}>')
                if lines:
                    msg = f"{len(lines)} commit hashes or journal words"
                    f.write(f"<failure message={quoteattr(msg)}>{escape(chr(10).join(lines))}</failure>")
                f.write("</testcase>\n")
            f.write("</testsuite>\n")
    print(f"journal check: {sum(len(l) for _, l in cases)} hits in {failed} of {len(cases)} places")
    return 1 if failed else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
