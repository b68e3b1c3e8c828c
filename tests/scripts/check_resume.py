#!/usr/bin/env python3
"""Resume and kill tests: a run continued from its checkpoint writes what the run straight through writes.

    check_resume.py SABO WORKDIR --end T [--split T1 | --kills K [--signal KILL|INT|TERM]] [--threads N]
                    [--resume-threads M] [--fault-checkpoint C] [--launcher "mpiexec -n 2"]
                    -- CASE [sabo run arguments ...]

1. The reference: `sabo run CASE ... --set case.end_time_s=T` straight through (into WORKDIR/straight).
2. Either --split T1: the same run to T1, then `sabo resume` to T; or --kills K: the same run killed with
   SIGKILL (or stopped with SIGINT/SIGTERM: then it must exit 130) K times at random moments (each time resumed: `sabo resume`, or `sabo run` again when no
   checkpoint was written yet), then resumed to the end; with --fault-checkpoint C the first attempt kills
   itself inside its C-th checkpoint write (after its bytes, before the rename). Into WORKDIR/resumed.
3. Every file of the reference (series, pile and arching tables, force maps, frames, .pvd series) must be
   there, bit for bit, and summary.json must hold the same values except the wall time, the rates and the
   thread count. The log, the report, the checkpoint and the run's request are not compared.
With --launcher every sabo command runs under it (a run divided among MPI ranks, its checkpoint one file per
rank).
"""
import argparse
import json
import os
import random
import shutil
import signal
import subprocess
import sys
import time

NOT_COMPARED = {"sabo.log", "checkpoint.bin", "checkpoint.bin.tmp", "resume.toml", "report.md", ".sabo.lock"}
VOLATILE_KEYS = {"wall_time_s", "timing", "threads", "particle_steps_per_s", "cell_updates_per_s", "mlups",
                 "mpi_exchange_fraction", "mpi_time_imbalance"}  # (faces move by a model, not a clock: compared)


def compare(straight: str, resumed: str) -> list[str]:
    problems = []
    for root, _, files in os.walk(straight):
        for name in files:
            a = os.path.join(root, name)
            rel = os.path.relpath(a, straight)
            b = os.path.join(resumed, rel)
            if name in NOT_COMPARED or name.endswith(".png") or name.startswith("checkpoint.rank"):
                continue
            if not os.path.exists(b):
                problems.append(f"{rel}: missing after the resume")
            elif name == "summary.json":
                with open(a, encoding="utf-8") as fa, open(b, encoding="utf-8") as fb:
                    ja, jb = json.load(fa), json.load(fb)
                for key in sorted(set(ja) | set(jb)):
                    if key in VOLATILE_KEYS or key.endswith("_per_s"):
                        continue
                    if json.dumps(ja.get(key)) != json.dumps(jb.get(key)):
                        problems.append(f"summary.json {key}: {ja.get(key)} straight, {jb.get(key)} resumed")
            else:
                with open(a, "rb") as fa, open(b, "rb") as fb:
                    if fa.read() != fb.read():
                        problems.append(f"{rel}: differs")
    return problems


def run(cmd: list[str]) -> int:
    print("$", " ".join(cmd), flush=True)
    return subprocess.run(cmd, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL).returncode


def status(out_dir: str) -> str | None:
    """The status the run in out_dir wrote in its summary (completed, interrupted, failed), if any."""
    try:
        with open(os.path.join(out_dir, "summary.json")) as f:
            return json.load(f).get("status")
    except (OSError, ValueError):
        return None


def completed(out_dir: str) -> bool:
    return status(out_dir) == "completed"


def killed_run(cmd: list[str], after: float, sig: signal.Signals, out_dir: str, launcher: bool) -> int | None:
    """Starts cmd, sends it `sig` `after` seconds later; its exit code if it ended before, else None.
    A signal that comes after the run's last step (while it writes its final outputs) stops nothing:
    the run then completes with 0, which counts as having ended before the signal. Under a launcher
    (mpirun turns the signal into SIGTERM to the ranks and exits with a code of its own) the run's
    summary must say it was interrupted (or completed, or be absent: stopped while the ranks started)."""
    print(f"$ {' '.join(cmd)}   # {sig.name} after {after:.2f} s", flush=True)
    proc = subprocess.Popen(cmd, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    try:
        return proc.wait(timeout=after)
    except subprocess.TimeoutExpired:
        proc.send_signal(sig)
        code = proc.wait()
        if (code == 0 or launcher) and completed(out_dir):
            print("  the signal came after the last step: the run completed")
            return 0
        if sig != signal.SIGKILL and launcher and status(out_dir) not in ("interrupted", None):
            raise SystemExit(f"stopped by {sig.name}, the run's summary says {status(out_dir)}, not interrupted")
        if launcher and status(out_dir) is None:
            print("  the signal came while the ranks started: nothing ran")
        if sig != signal.SIGKILL and not launcher and code != 130:
            raise SystemExit(f"stopped by {sig.name}, the run exited with {code}, not 130")
        return None


def main() -> int:
    parser = argparse.ArgumentParser()
    parser.add_argument("sabo")
    parser.add_argument("workdir")
    parser.add_argument("--end", type=float, required=True)
    parser.add_argument("--split", type=float)
    parser.add_argument("--kills", type=int)
    parser.add_argument("--threads", type=int, default=2)
    parser.add_argument("--resume-threads", type=int)
    parser.add_argument("--fault-checkpoint", type=int)
    parser.add_argument("--signal", default="KILL", choices=["KILL", "INT", "TERM"])
    parser.add_argument("--seed", type=int, default=int(time.time()))
    parser.add_argument("--launcher", default="")
    if "--" not in sys.argv:
        parser.error("the case and its arguments follow --")
    split = sys.argv.index("--")
    a = parser.parse_args(sys.argv[1:split])
    case = sys.argv[split + 1:]
    sabo = [*a.launcher.split(), a.sabo]
    checkpoint = "checkpoint.rank0.bin" if a.launcher else "checkpoint.bin"
    if (a.split is None) == (a.kills is None):
        parser.error("give --split or --kills")
    shutil.rmtree(a.workdir, ignore_errors=True)
    straight, resumed = os.path.join(a.workdir, "straight"), os.path.join(a.workdir, "resumed")
    threads = ["--threads", str(a.threads)]
    resume_threads = ["--threads", str(a.resume_threads or a.threads)]
    end = ["--set", f"case.end_time_s={a.end}"]

    started = time.monotonic()
    if run([*sabo, "run", *case, *end, "--out", straight, *threads]) != 0:
        print("the straight run failed")
        return 1
    duration = time.monotonic() - started

    resume = [*sabo, "resume", resumed, *end, *resume_threads]
    if a.split is not None:
        if run([*sabo, "run", *case, "--set", f"case.end_time_s={a.split}", "--out", resumed, *threads]) != 0:
            print("the first part failed")
            return 1
        if run(resume) != 0:
            print("the resumed part failed")
            return 1
    else:
        rng = random.Random(a.seed)
        print(f"random kill moments from seed {a.seed} (the straight run took {duration:.2f} s)")
        first = [*sabo, "run", *case, *end, "--out", resumed, *threads]
        if a.fault_checkpoint:
            env = dict(os.environ, SABO_TEST_KILL_AT_CHECKPOINT=str(a.fault_checkpoint))
            print(f"$ {' '.join(first)}   # killed in its checkpoint {a.fault_checkpoint}", flush=True)
            code = subprocess.run(first, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL, env=env).returncode
            if code != -signal.SIGKILL or not os.path.exists(os.path.join(resumed, "checkpoint.bin.tmp")):
                print(f"the run was to kill itself while writing a checkpoint; it exited with {code}")
                return 1
        for k in range(a.kills):
            has_checkpoint = os.path.exists(os.path.join(resumed, checkpoint))
            code = killed_run(resume if has_checkpoint else first, rng.uniform(0.1, 0.8) * duration,
                              signal.Signals["SIG" + a.signal], resumed, bool(a.launcher))
            if code is not None:
                print(f"  ended before the kill (exit {code})")
                if code == 0:
                    break
        if run(resume if os.path.exists(os.path.join(resumed, checkpoint)) else first) != 0:
            print("the last resume failed")
            return 1

    problems = compare(straight, resumed)
    for p in problems:
        print(p)
    print("same outputs" if not problems else f"{len(problems)} differences")
    return 1 if problems else 0


if __name__ == "__main__":
    sys.exit(main())
