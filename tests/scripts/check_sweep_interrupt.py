#!/usr/bin/env python3
# SPDX-License-Identifier: MIT
"""A stop signal to a sweep (or to mpirun running one) reaches its running cases once: each writes its
checkpoint and ends as `interrupted`, and the sweep exits with 130 without a report.

    check_sweep_interrupt.py [--launcher] OUT_DIR COMMAND...     (COMMAND writes the sweep into OUT_DIR)

--launcher: COMMAND is an MPI launcher, whose exit code on a stop is its own (OpenMPI's mpirun: 1): any
non-zero code is accepted; each rank's 130 shows in the index and the messages.
"""
import csv
import os
import shutil
import signal
import subprocess
import sys
import time


def main():
    launcher = sys.argv[1] == "--launcher"
    args = sys.argv[2:] if launcher else sys.argv[1:]
    out, command = args[0], args[1:]
    shutil.rmtree(out, ignore_errors=True)
    proc = subprocess.Popen(command, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True)
    deadline = time.monotonic() + 60
    running = []
    while time.monotonic() < deadline and not running:  # wait until a case has a checkpoint-able state
        time.sleep(0.5)
        if os.path.exists(os.path.join(out, "sweep_cases.csv")):
            with open(os.path.join(out, "sweep_cases.csv")) as f:
                running = [r for r in csv.DictReader(f) if r["status"] == "running"]
    assert running, "no case started within 60 s"
    time.sleep(1.5)
    proc.send_signal(signal.SIGINT)
    output, _ = proc.communicate(timeout=120)
    print(output)
    if launcher:
        assert proc.returncode != 0, "the launcher exited with 0 after a stop"
    else:
        assert proc.returncode == 130, f"exit {proc.returncode}, expected 130"
    with open(os.path.join(out, "sweep_cases.csv")) as f:
        index = list(csv.DictReader(f))
    stopped = [r for r in index if r["status"] == "interrupted"]
    assert stopped, f"no case interrupted: {index}"
    for r in stopped:
        folder = os.path.join(out, r["dir"])
        assert os.path.exists(os.path.join(folder, "checkpoint.bin")), f"{r['case']}: no checkpoint"
        with open(os.path.join(folder, "console.log")) as f:
            log = f.read()
        assert "second stop signal" not in log, f"{r['case']}: the signal came twice"
    assert not os.path.exists(os.path.join(out, "sweep.csv")), "a report of an interrupted sweep"
    print(f"interrupted cleanly: {len(stopped)} case(s) stopped with a checkpoint")


if __name__ == "__main__":
    main()
