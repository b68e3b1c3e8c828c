#!/usr/bin/env python3
"""Corrupt, foreign and missing checkpoints are refused by `sabo resume` with a message saying why
(exit 2, within a few seconds), and the run folder's outputs are left as they were.

    check_bad_checkpoint.py SABO WORKDIR CASE [sabo run arguments ...]

Runs CASE once into WORKDIR/run, then for each damage (a copy of the folder each time): the checkpoint
truncated, cut to its first bytes, its magic of another version, a byte appended, a bit flipped, replaced
by a text file, a list length made huge, deleted; the checkpoint of another case (the same run with other
--set keys); resume.toml removed.
"""
import os
import re
import shutil
import subprocess
import sys


def resume(sabo: str, folder: str, *extra: str) -> tuple[int, str]:
    run = subprocess.run([sabo, "resume", folder, *extra], capture_output=True, text=True, timeout=10)
    return run.returncode, run.stdout + run.stderr


def main() -> int:
    sabo, work, case, args = sys.argv[1], sys.argv[2], sys.argv[3], sys.argv[4:]
    shutil.rmtree(work, ignore_errors=True)
    original = os.path.join(work, "run")
    other = os.path.join(work, "other")
    base = [sabo, "run", case, *args, "--set", "output.report=false"]
    if subprocess.run([*base, "--out", original], capture_output=True).returncode != 0:
        print("the run failed")
        return 1
    if subprocess.run([*base, "--set", "contact.restitution=0.3", "--out", other],
                      capture_output=True).returncode != 0:
        print("the other run failed")
        return 1
    with open(os.path.join(original, "checkpoint.bin"), "rb") as f:
        good = f.read()

    def write(data: bytes):
        return lambda folder: open(os.path.join(folder, "checkpoint.bin"), "wb").write(data)

    damages = [
        ("truncated", write(good[: len(good) // 2]), r"damaged checkpoint"),
        ("cut to its first bytes", write(good[:5]), r"not a sabo checkpoint \(too short\)"),
        ("another layout version", write(good[:7] + b"3" + good[8:]), r"not a sabo checkpoint of this version"),
        ("a byte appended", write(good + b"\0"), r"damaged checkpoint"),
        ("a bit flipped", write(good[: len(good) // 2] + bytes([good[len(good) // 2] ^ 4]) + good[len(good) // 2 + 1:]),
         r"damaged checkpoint"),
        ("a text file", write(b"hello, I am not a checkpoint\n" * 10), r"not a sabo checkpoint"),
        ("a huge list length", write(good[:8] + b"\xff" * 8 + good[16:]), r"damaged checkpoint"),
        ("deleted", lambda folder: os.remove(os.path.join(folder, "checkpoint.bin")), r"no checkpoint .* to resume from"),
        ("of another case",
         lambda folder: shutil.copy(os.path.join(other, "checkpoint.bin"), os.path.join(folder, "checkpoint.bin")),
         r"written for another case: in \[contact\] it has 'restitution = 0.(3|29)"),
        ("no resume.toml", lambda folder: os.remove(os.path.join(folder, "resume.toml")), r"not a sabo run folder"),
    ]
    failures = 0
    for k, (name, damage, expect) in enumerate(damages):
        folder = os.path.join(work, f"damaged_{k}")
        shutil.copytree(original, folder)
        damage(folder)
        with open(os.path.join(folder, "series.csv"), "rb") as f:
            series = f.read()
        code, output = resume(sabo, folder, "--set", "case.end_time_s=2")
        with open(os.path.join(folder, "series.csv"), "rb") as f:
            untouched = f.read() == series
        ok = code == 2 and re.search(expect, output) is not None and untouched
        print(f"{'ok' if ok else 'FAILED'}: checkpoint {name}: exit {code}; series untouched: {untouched}")
        last = [line for line in output.splitlines() if "error" in line]
        print("   ", last[-1] if last else output.strip().splitlines()[-1:])
        failures += 0 if ok else 1
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
