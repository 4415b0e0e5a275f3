#!/usr/bin/env python3
"""Every relative link and image in README.md and docs/*.md (and the other Markdown files the
repository ships) must resolve to a file or directory inside the repository. Absolute URLs and
in-page anchors are not checked. Exit 1 with one line per broken link."""
import re
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
FILES = [ROOT / "README.md", *sorted((ROOT / "docs").glob("*.md")),
         ROOT / "sweeps" / "README.md", ROOT / "outputs" / "README.md"]
LINK = re.compile(r"!?\[[^\]]*\]\(([^)\s]+)(?:\s+\"[^\"]*\")?\)")
FENCE = re.compile(r"^```.*?^```", re.S | re.M)


def main():
    bad, n = [], 0
    for f in FILES:
        if not f.exists():
            continue
        text = FENCE.sub("", f.read_text(encoding="utf-8"))
        for m in LINK.finditer(text):
            target = m.group(1)
            if re.match(r"^[a-z]+:", target) or target.startswith("#"):
                continue
            n += 1
            path = (f.parent / target.split("#")[0]).resolve()
            if not path.exists():
                bad.append(f"{f.relative_to(ROOT)}: broken link {target}")
            elif ROOT not in path.parents and path != ROOT:
                bad.append(f"{f.relative_to(ROOT)}: {target} points outside the repository")
    for b in bad:
        print(b)
    print(f"links: {n} relative links checked, {len(bad)} broken")
    return 1 if bad else 0


if __name__ == "__main__":
    sys.exit(main())
