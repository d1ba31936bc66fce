"""The lines of whirl's sources (src/) that a coverage build has executed so far: every .gcda file
under BUILD (make BUILD=BUILD OPT=-O1 XCFLAGS=--coverage XLDFLAGS=--coverage), read by gcov's
JSON format, printed as "FILE:LINE", one per line, sorted. Used by tests/tools/coverage_unique.sh.

    /usr/bin/python3 tests/tools/coverage_lines.py BUILD > lines.txt
"""
import json
import os
import subprocess
import sys


def main():
    if len(sys.argv) != 2:
        sys.exit("usage: coverage_lines.py BUILD")
    build = os.path.abspath(sys.argv[1])
    root = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
    gcda = [os.path.join(d, f) for d, _, fs in os.walk(os.path.join(build, "src"))
            for f in fs if f.endswith(".gcda")]
    lines = set()
    for i in range(0, len(gcda), 50):
        out = subprocess.run(["gcov", "--json-format", "--stdout"] + gcda[i:i + 50], cwd=root,
                             stdout=subprocess.PIPE, stderr=subprocess.DEVNULL, check=True).stdout
        for doc in out.decode().splitlines():
            if not doc.strip():
                continue
            for f in json.loads(doc)["files"]:
                name = os.path.relpath(os.path.join(root, f["file"]), root)
                if not name.startswith("src/"):
                    continue
                lines.update("%s:%d" % (name, l["line_number"]) for l in f["lines"] if l["count"] > 0)
    sys.stdout.write("".join(l + "\n" for l in sorted(lines, key=lambda s: s.encode())))


if __name__ == "__main__":
    main()
