#!/usr/bin/env python3
"""Rewrites the key tables of docs/problem-file.md from the option tables of the program.

Usage: update_problem_file_keys.py FRICON [DOC]   (DOC: docs/problem-file.md beside this script)

Each table in the page sits between `<!-- keys: ID -->` and `<!-- /keys -->`, ID a section as
`fricon keys` names it (top, mesh, material, contact, contact.obstacle, contact.friction, solver,
output, [[dirichlet]], [[traction]], [[material]]); the block is replaced by `FRICON keys ID`.
The unit test OptionTables.DocsShowTheTables fails while the page and the tables differ.
"""
import pathlib
import re
import subprocess
import sys

BLOCK = re.compile(r"(<!-- keys: (?P<id>[^ ]+) -->\n)(?P<body>.*?)(<!-- /keys -->)", re.S)


def main():
    fricon = sys.argv[1]
    doc = pathlib.Path(sys.argv[2]) if len(sys.argv) > 2 else \
        pathlib.Path(__file__).resolve().parent.parent / "docs" / "problem-file.md"
    text = doc.read_text(encoding="utf-8")

    def table(match):
        out = subprocess.run([fricon, "keys", match["id"]], capture_output=True, text=True,
                             check=True).stdout
        return match.group(1) + out + match.group(4)

    new, n = BLOCK.subn(table, text)
    doc.write_text(new, encoding="utf-8")
    print(f"{doc}: {n} key tables written")


if __name__ == "__main__":
    main()
