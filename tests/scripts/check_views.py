#!/usr/bin/env python3
# SPDX-License-Identifier: MIT
"""python/view.py renders a run folder's standard views: side.png, oblique.png, barrier.png and animation.gif
exist, each image shows the scene (not a blank window: > 3 % of the pixels not background), the animation has
one image per frame taken, and a run with a fluid shows its free surface (bluish pixels).

    check_views.py PYTHON_DIR RUN_DIR [RUN_DIR...]
"""
import os
import subprocess
import sys
import xml.etree.ElementTree as ET

from PIL import Image


def drawn_fraction(path):
    image = Image.open(path).convert("RGB")
    pixels = list(image.getdata())
    return sum(1 for p in pixels if min(p) < 245) / len(pixels)


def bluish_fraction(path):
    pixels = list(Image.open(path).convert("RGB").getdata())
    return sum(1 for r, g, b in pixels if b > r + 40 and b > g + 15 and b > 120) / len(pixels)


def main() -> int:
    python_dir, runs = sys.argv[1], sys.argv[2:]
    failures = 0
    for run in runs:
        code = subprocess.call([sys.executable, os.path.join(python_dir, "view.py"), run, "--size", "480x270",
                                "--every", "2"])
        views = os.path.join(run, "views")
        frames = len(list(ET.parse(os.path.join(run, "particles.pvd")).getroot().iter("DataSet")))
        problems = [] if code == 0 else [f"view.py exited {code}"]
        for name in ("side.png", "oblique.png", "barrier.png"):
            path = os.path.join(views, name)
            if not os.path.exists(path):
                problems.append(f"no {name}")
            elif drawn_fraction(path) < 0.03:
                problems.append(f"{name} is nearly blank ({100 * drawn_fraction(path):.1f} % drawn)")
        gif = os.path.join(views, "animation.gif")
        shown = Image.open(gif).n_frames if os.path.exists(gif) else 0
        if shown != (frames + 1) // 2:
            problems.append(f"animation.gif has {shown} images, {(frames + 1) // 2} expected")
        if os.path.exists(os.path.join(run, "fluid.pvd")):
            blue = bluish_fraction(os.path.join(views, "oblique.png"))
            if blue < 0.005:
                problems.append(f"no free surface in oblique.png ({100 * blue:.2f} % bluish pixels)")
        print(f"{run}: {'; '.join(problems) if problems else 'views ok'} ({shown} animation images)")
        failures += bool(problems)
    print("views rendered" if failures == 0 else f"{failures} run folder(s) not rendered right")
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
