# SPDX-License-Identifier: MIT
"""Helpers shared by report.py and sweep_report.py."""
import os


def write_markdown(out, name, lines, images):
    """Appends one section per (title, png) to `lines` and writes out/name atomically."""
    for title, png in images:
        lines += ["", f"## {title}", "", f"![{title}]({png})"]
    tmp = os.path.join(out, name + ".tmp")
    with open(tmp, "w") as f:
        f.write("\n".join(lines) + "\n")
    os.replace(tmp, os.path.join(out, name))
