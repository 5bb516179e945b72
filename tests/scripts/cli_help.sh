#!/usr/bin/env bash
# `--help` tells what the documentation does: every flag a documented
# command line (README.md, docs/*.md) gives a command appears in that
# command's --help, and so does every option the layout parser accepts
# after a uv layout's comma (core/layouts/layout.cc names them in its error);
# `eval --help` marks nothing REQUIRED but the store; `--version` is the
# CMake project's version.
set -euo pipefail
WB=$1
SRC=${WB_SOURCE_DIR:?}
/usr/bin/python3 - "$WB" "$SRC" <<'PY'
import re
import subprocess
import sys
from pathlib import Path

wb, src = sys.argv[1], Path(sys.argv[2])
help_of = {}


def helptext(command):
    if command not in help_of:
        help_of[command] = subprocess.run([wb, command, "--help"], capture_output=True, text=True,
                                          check=True).stdout
    return help_of[command]


commands = set(re.findall(r"^  (\w+)\s", subprocess.run([wb, "--help"], capture_output=True, text=True,
                                                          check=True).stdout, re.M))
assert {"bake", "relight", "eval", "submit", "watch", "status"} <= commands, commands
missing, checked = [], 0
for doc in [src / "README.md", *sorted((src / "docs").glob("*.md"))]:
    lines = doc.read_text().splitlines()
    i = 0
    while i < len(lines):
        line = lines[i]
        while line.rstrip().endswith("\\") and i + 1 < len(lines):  # a continued command line
            i += 1
            line = line.rstrip()[:-1] + " " + lines[i]
        i += 1
        for m in re.finditer(r"\bwavebake (\w+)((?:\s+[^\s|;&`]+)*)", line):
            command, rest = m.group(1), m.group(2)
            if command not in commands:
                continue
            for flag in re.findall(r"(?<![\w-])(--[a-z][a-z0-9-]*)", rest):
                checked += 1
                if not re.search(rf"(?<![\w-]){re.escape(flag)}(?![\w-])", helptext(command)):
                    missing.append(f"{doc.name}: wavebake {command} {flag}")
assert checked > 50, checked
assert not missing, "documented but not in --help:\n" + "\n".join(sorted(set(missing)))

# The uv layout options, as the parser lists them in its error.
listed = re.search(r"\(allow-overlap, fill=([a-z|-]+)\)", (src / "core" / "layouts" / "layout.cc").read_text())
assert listed, "core/layouts/layout.cc no longer lists its uv options"
bake = helptext("bake")
for option in [",allow-overlap", ",fill="] + listed.group(1).split("|"):
    assert option in bake, f"bake --help does not mention {option}"

eval_help = helptext("eval")
required = [line for line in eval_help.splitlines() if "REQUIRED" in line and "--" in line]
assert not required, required

version = subprocess.run([wb, "--version"], capture_output=True, text=True, check=True).stdout.strip()
project = re.search(r"project\(wavebake VERSION ([0-9.]+)", (src / "CMakeLists.txt").read_text())
assert version.endswith(project.group(1)), (version, project.group(1))
print(f"{checked} documented flags found in --help; version {version}")
PY
