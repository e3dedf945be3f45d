#!/usr/bin/env python3
"""Feeds `gjkdem query` mutated versions of valid pair lines (deterministic
seed): it must not crash or hang, must answer every non-skipped line in order
(a result or an error object naming the line), and must exit 0 or 1.
Usage: cli_fuzz.py GJKDEM EXAMPLE.jsonl"""
import json
import random
import subprocess
import sys

gjkdem, example = sys.argv[1], sys.argv[2]
rng = random.Random(12345)
base = [l for l in open(example) if l.strip() and not l.startswith("#")]
junk = ["", "-1", "1e400", "NaN", "null", "[]", "{}", '"x"', "[1,2]", "[1,2,3,4]", "true", "-0", "1e-320"]
lines = []
for k in range(400):
    line = rng.choice(base)
    mode = rng.randrange(4)
    if mode == 0:  # cut the line short
        line = line[: rng.randrange(len(line))]
    elif mode == 1:  # replace a number by junk
        toks = line.split(",")
        i = rng.randrange(len(toks))
        toks[i] = toks[i].replace(toks[i].strip("[]{} \n\"").split(":")[-1], rng.choice(junk), 1) if toks[i].strip() else toks[i]
        line = ",".join(toks)
    elif mode == 2:  # flip one character
        i = rng.randrange(len(line))
        line = line[:i] + chr(rng.randrange(32, 127)) + line[i + 1:]
    else:  # structured mutation
        try:
            obj = json.loads(line)
            s = obj[rng.choice("ab")]
            key = rng.choice(list(s.keys()))
            s[key] = rng.choice([None, -1.0, 0.0, 1e300, [], [0, 0], "z", {"a": 1}, [[0, 0, 0]] * rng.randrange(0, 4)])
            line = json.dumps(obj)
        except ValueError:
            pass
    lines.append(line.replace("\n", " ").strip())
payload = "\n".join(lines) + "\n"
expected = sum(1 for l in lines if l.strip() and not l.lstrip().startswith("#"))
try:
    proc = subprocess.run([gjkdem, "query"], input=payload, capture_output=True, text=True, timeout=120)
except subprocess.TimeoutExpired:
    print("FAIL: gjkdem query hung"); sys.exit(1)
out = proc.stdout.splitlines()
ok = proc.returncode in (0, 1) and len(out) == expected
for o in out:
    r = json.loads(o)  # every output line is JSON
    ok &= ("error" in r and "line " in r["error"]) or "intersect" in r
print("%d lines in, %d out, exit %d" % (expected, len(out), proc.returncode))
print("1 passed, 0 failed" if ok else "0 passed, 1 failed")
sys.exit(0 if ok else 1)
