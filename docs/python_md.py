"""Writes docs/python.md from a run of docs/python_example.py: each
`# %% Title` cell becomes a section (its leading `# ` lines the prose, the
rest the code) followed by what that cell printed. Run with the installed
package, from the repository root:

    v/bin/python docs/python_md.py OUT_DIR > docs/python.md
"""
import contextlib
import io
import os
import platform
import sys
from pathlib import Path

HERE = Path(__file__).resolve().parent
EXAMPLE = HERE / "python_example.py"

HEAD = """# wavebake from Python

`import wavebake`: the package `python/wavebake` (typed: `__init__.pyi`,
`py.typed`) around its pybind11 extension, over the same libraries as the
command line. Install it into a venv (README.md, *Python*):

```sh
python3 -m venv --system-site-packages v && v/bin/pip install --no-build-isolation .
```

This page is written by `docs/python_md.py`, which runs
`docs/python_example.py` cell by cell:

```sh
WB_SHARED_DATA=../shared/data v/bin/python docs/python_md.py out > docs/python.md
```

The output under each cell is what it printed ({machine}).
"""

TAIL = """
## A coordinator's jobs

(Not run above: it needs a running coordinator.)

```python
client = wavebake.Client("127.0.0.1:7433", token_file="out/token")
job = client.submit("../shared/data/models/bunny.obj", layout="hilbert:64x64", light_res=16)
for event in client.watch(job["id"]):          # every event to the end, reconnecting
    print(event["kind"], event["phase"], event["tasks_done"], "/", event["tasks_total"])
client.fetch(job["id"], "out/bunny.wbk")        # verified; never over an existing path
print(client.status(job["id"])["phase"])        # "DONE"; job ids may be str or int
```

`client.jobs()`, `client.cancel(id)` too. Dropping a `watch` iterator early
stops its stream at once.
"""


def cells(source):
    """(title, prose lines, code lines) per `# %%` cell; the docstring before
    the first cell is left out."""
    out, current = [], None
    for line in source.splitlines():
        if line.startswith("# %% "):
            current = [line[5:].strip(), [], []]
            out.append(current)
        elif current is not None:
            if not current[2] and line.startswith("#"):
                current[1].append(line[2:] if line.startswith("# ") else "")
            else:
                current[2].append(line)
    for cell in out:
        while cell[2] and not cell[2][-1].strip():
            cell[2].pop()
    return out


def main():
    sys.argv = [str(EXAMPLE), *sys.argv[1:]]
    namespace = {"__name__": "__main__", "__file__": str(EXAMPLE)}
    cores = os.cpu_count()
    page = [HEAD.format(machine=f"{platform.python_implementation()} {platform.python_version()}, "
                                f"{cores} cores shared with other work")]
    for title, prose, code in cells(EXAMPLE.read_text()):
        printed = io.StringIO()
        with contextlib.redirect_stdout(printed):
            exec(compile("\n".join(code) + "\n", str(EXAMPLE), "exec"), namespace)
        page.append(f"## {title}\n")
        if prose:
            page.append("\n".join(prose).strip() + "\n")
        page.append("```python\n" + "\n".join(code).strip("\n") + "\n```")
        if printed.getvalue():
            page.append("```\n" + printed.getvalue().rstrip("\n") + "\n```")
        page.append("")
    image = Path(sys.argv[1] if len(sys.argv) > 1 else "out") / "python_relight.png"
    if image.exists():
        page.append("![four frames of cubes-wall under grace.hdr, turned by 90 degrees each]"
                    "(images/python_relight.png)\n")
    page.append(TAIL)
    sys.stdout.write("\n".join(page).rstrip("\n") + "\n")


if __name__ == "__main__":
    main()
