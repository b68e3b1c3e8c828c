#!/usr/bin/env python3
# SPDX-License-Identifier: MIT
"""Asserts the grain accounting of a sandpile run folder with sandpile.remove_drained (the default):
some grains were taken out below the plate, every grain is either still in the run (final_grains.csv)
or removed, and the plate holds no more grains than the run.
Usage: check_sandpile_removal.py DIR"""
import csv
import json
import os
import sys

folder = sys.argv[1]
summary = json.load(open(os.path.join(folder, "summary.json")))
left = list(csv.DictReader(open(os.path.join(folder, "final_grains.csv"))))
removed = summary["grains_removed_below_plate"]
total = summary["particles"]
print(f"{total} grains: {len(left)} left in the run, {removed} removed below the plate, "
      f"{summary['grains_on_plate']} on the plate")
if removed <= 0:
    sys.exit("no grain was removed: the drained grains were not taken out")
if len(left) + removed != total:
    sys.exit(f"grains lost or duplicated: {len(left)} + {removed} != {total}")
if summary["grains_on_plate"] > len(left):
    sys.exit("more grains on the plate than in the run")
print("grain accounting consistent")
