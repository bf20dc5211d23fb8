#!/usr/bin/python3
"""The user guide documents every deck key the code knows, and no other.

Usage: check.py IMPACT3D_EXE docs/user-guide.md
Runs `impact3d --keys`, then checks that each group has a '### &group' section
whose table rows (| `key` | ...) name exactly the code's keys, in one table
(a blank line between rows would split it in two when rendered).
"""
import re
import subprocess
import sys

exe, guide = sys.argv[1], sys.argv[2]
out = subprocess.run([exe, "--keys"], capture_output=True, text=True, check=True).stdout
code = {}
for line in out.splitlines():
    name, _, keys = line.partition(":")
    code[name.strip().lstrip("&")] = set(keys.split())
text = open(guide).read()
split = []
sections = re.split(r"^### &", text, flags=re.M)[1:]
doc = {}
for sec in sections:
    name = sec.split()[0]
    keys = set()
    for row in re.findall(r"^\| (`[^|]*`) \|", sec, flags=re.M):
        keys.update(re.findall(r"`([a-z_0-9]+)`", row))
    doc[name] = keys
    lines = sec.splitlines()
    rows = [i for i, line in enumerate(lines) if re.match(r"^\| `", line)]
    if rows and not all(line.startswith("|") for line in lines[rows[0]:rows[-1] + 1]):
        split.append(name)
failed = 0
for name in split:
    failed += 1
    print("FAIL &%s: its key table is split (a line that is not a table row between rows)"
          % name)
for group, keys in code.items():
    missing = keys - doc.get(group, set())
    extra = doc.get(group, set()) - keys
    ok = not missing and not extra
    failed += not ok
    print(("PASS" if ok else "FAIL") + " &%s: %d keys" % (group, len(keys))
          + ("" if ok else " undocumented: %s; not in the code: %s"
             % (sorted(missing), sorted(extra))))
print("%d passed, %d failed" % (len(code) - failed + len(split), failed))
sys.exit(1 if failed or not code else 0)
