#!/usr/bin/env python3
"""Runs the README's examples against the built binary, so they stay copy-pasteable.

Usage: readme_examples.py SURFCERT_BINARY README.md [-v]

An example is a ```sh block preceded by a marker comment

    <!-- example: NAME exit=N output=json|jsonl|text -->

Its commands run with bash in the README's directory, `build/app/surfcert` replaced by the
binary under test. Checked: the exit status is the documented N; with output=json the whole
stdout is one JSON value, with output=jsonl every stdout line is a JSON object with a "status".
No prose is asserted (the README's text may change freely). Also checked: every ```sh block
that runs build/app/surfcert is marked (so a new example cannot silently go untested), and
there are at least five examples.
"""
import json
import os
import re
import subprocess
import sys

MARKER = re.compile(r"^<!--\s*example:\s*(\S+)\s+exit=(\d+)\s+output=(json|jsonl|text)\s*-->\s*$")
BINARY_IN_README = "build/app/surfcert"


def examples(lines):
    """[(name, exit, output, script, line_no)] and the unmarked sh blocks running the binary."""
    found, unmarked = [], []
    i = 0
    pending = None
    while i < len(lines):
        m = MARKER.match(lines[i].strip())
        if m:
            pending = (m.group(1), int(m.group(2)), m.group(3), i + 1)
            i += 1
            continue
        if lines[i].strip() == "```sh":
            start = i + 1
            j = start
            while j < len(lines) and lines[j].strip() != "```":
                j += 1
            body = "".join(lines[start:j])
            if pending:
                name, code, output, at = pending
                found.append((name, code, output, body, at))
            elif BINARY_IN_README in body:
                unmarked.append(start)
            pending = None
            i = j + 1
            continue
        if lines[i].strip():
            pending = None  # a marker applies only to the block right after it
        i += 1
    return found, unmarked


def check_output(output, out):
    """An error message, or None when the output has the documented form."""
    if output == "json":
        try:
            json.loads(out)
        except ValueError as e:
            return "stdout is not one JSON value: %s" % e
    elif output == "jsonl":
        lines = [l for l in out.splitlines() if l.strip()]
        if not lines:
            return "no JSON lines on stdout"
        for k, l in enumerate(lines, 1):
            try:
                o = json.loads(l)
            except ValueError as e:
                return "stdout line %d is not JSON: %s" % (k, e)
            if not isinstance(o, dict) or "status" not in o:
                return "stdout line %d is not an answer object with a status" % k
    elif not out.strip():
        return "no output"
    return None


def main():
    if len(sys.argv) < 3:
        print(__doc__)
        return 2
    binary = os.path.abspath(sys.argv[1])
    readme = os.path.abspath(sys.argv[2])
    verbose = "-v" in sys.argv[3:]
    with open(readme, encoding="utf-8") as f:
        lines = f.readlines()
    found, unmarked = examples(lines)
    failures = []
    for at in unmarked:
        failures.append("README.md:%d: a sh block runs %s without an example marker"
                        % (at, BINARY_IN_README))
    if len(found) < 5:
        failures.append("expected at least 5 marked examples, found %d" % len(found))
    for name, code, output, body, at in found:
        script = body.replace(BINARY_IN_README, binary)
        try:
            p = subprocess.run(["bash", "-c", "set -o pipefail\n" + script],
                               cwd=os.path.dirname(readme), capture_output=True, text=True,
                               timeout=300)
        except subprocess.TimeoutExpired:
            failures.append("%s (README.md:%d): timed out" % (name, at))
            continue
        problem = None
        if p.returncode != code:
            problem = "exit status %d, documented %d" % (p.returncode, code)
        else:
            problem = check_output(output, p.stdout)
        if problem:
            failures.append("%s (README.md:%d): %s\nstderr: %s" % (name, at, problem,
                                                                  p.stderr[-2000:]))
        elif verbose:
            print("ok %s: exit %d, %d bytes of %s" % (name, code, len(p.stdout), output))
    for f in failures:
        print("FAIL " + f)
    print("%d examples, %d failures" % (len(found), len(failures)))
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
