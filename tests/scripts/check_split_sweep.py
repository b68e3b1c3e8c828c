#!/usr/bin/env python3
# SPDX-License-Identifier: MIT
"""A sweep split over shards or MPI ranks gives the folder a sweep on one machine gives.

    check_split_sweep.py SINGLE_DIR SPLIT_DIR [CONSOLE_LOG]

The index (sweep_cases.csv) and the table (sweep.csv, less its wall times) are equal, every case has
completed, and each case's series.csv is the same byte for byte (the same binary, the same threads).
CONSOLE_LOG (the split sweep's messages): every case was run once, by one rank or shard.
"""
import csv
import filecmp
import os
import re
import sys


def rows(path, drop=()):
    with open(path) as f:
        table = list(csv.DictReader(f))
    return [{k: v for k, v in r.items() if k not in drop} for r in table]


def main():
    single, split = sys.argv[1], sys.argv[2]
    index = rows(os.path.join(split, "sweep_cases.csv"))
    assert index == rows(os.path.join(single, "sweep_cases.csv")), "the indexes differ"
    assert index and all(r["status"] == "completed" for r in index), index
    assert rows(os.path.join(split, "sweep.csv"), {"wall_time_s"}) == rows(os.path.join(single, "sweep.csv"),
                                                                           {"wall_time_s"}), "sweep.csv differs"
    for r in index:
        a, b = (os.path.join(d, r["dir"], "series.csv") for d in (single, split))
        assert filecmp.cmp(a, b, shallow=False), f"{r['case']}: series.csv differs"
        with open(os.path.join(split, r["dir"], "sweep_status.txt")) as f:
            assert f.read().strip() == "completed"
    if len(sys.argv) > 3:
        with open(sys.argv[3]) as f:
            runs = re.findall(r"\] (\S+): completed$", f.read(), re.MULTILINE)
        for r in index:
            assert runs.count(r["case"]) == 1, f"{r['case']} ran {runs.count(r['case'])} times"
    print(f"split sweep matches the single one: {len(index)} cases")


if __name__ == "__main__":
    main()
