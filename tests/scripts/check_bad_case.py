#!/usr/bin/env python3
"""Runs `sabo check` (or `sabo run`, with `# command: run`) on one case file of tests/bad_cases/ and
asserts what its header promises: the message (`# expect: REGEX`, searched in stdout + stderr) and the
exit code (`# exit: N`), both within a few seconds (a size that is refused only after allocating, or a
hang, fails the test)."""
import re
import subprocess
import sys


def main() -> int:
    sabo, case = sys.argv[1], sys.argv[2]
    expect, code, command = None, None, "check"
    with open(case, encoding="utf-8") as f:
        for line in f:
            if not line.startswith("#"):
                break
            if line.startswith("# expect: "):
                expect = line[len("# expect: "):].rstrip("\n")
            elif line.startswith("# exit: "):
                code = int(line[len("# exit: "):])
            elif line.startswith("# command: "):
                command = line[len("# command: "):].strip()
    if expect is None or code is None:
        print(f"{case}: the header needs '# expect: REGEX' and '# exit: N'")
        return 1
    try:
        run = subprocess.run([sabo, command, case], capture_output=True, text=True, timeout=5)
    except subprocess.TimeoutExpired:
        print(f"{case}: sabo {command} did not answer within 5 s")
        return 1
    output = run.stdout + run.stderr
    print(output, end="")
    if run.returncode != code:
        print(f"{case}: exit code {run.returncode}, expected {code}")
        return 1
    if re.search(expect, output) is None:
        print(f"{case}: no match for /{expect}/")
        return 1
    return 0


if __name__ == "__main__":
    sys.exit(main())
