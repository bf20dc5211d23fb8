#!/usr/bin/python3
"""The user guide documents every deck key the code knows, and no other, with
the code's defaults.

Usage: check.py IMPACT3D_EXE docs/user-guide.md
Runs `impact3d --keys` (one key per line: '&group | key | type | default |
units | meaning', from the packages' key tables), then checks that each group
has a '### &group' section whose table rows (| `key` | default | meaning |)
name exactly the code's keys, in one table (a blank line between rows would
split it in two when rendered), and that a row naming one key gives the
code's default for it (markup aside; rows naming several keys, such as `x`, `y`, `z`, are
checked for their keys only). Every key must also have a known type.
"""
import re
import subprocess
import sys

TYPES = {"real", "integer", "logical", "text"}

exe, guide = sys.argv[1], sys.argv[2]
out = subprocess.run([exe, "--keys"], capture_output=True, text=True, check=True).stdout
code = {}
defaults = {}
failed = 0
for line in out.splitlines():
    fields = [f.strip() for f in line.split(" | ")]
    if len(fields) != 6 or not fields[0].startswith("&"):
        failed += 1
        print("FAIL --keys line is not '&group | key | type | default | units | meaning': "
              + line)
        continue
    group, key, kind, default, _units, meaning = fields
    group = group.lstrip("&")
    code.setdefault(group, set()).add(key)
    defaults[group, key] = default
    if kind not in TYPES or not default or not meaning:
        failed += 1
        print("FAIL &%s: %s: type '%s', default '%s', meaning '%s'"
              % (group, key, kind, default, meaning))
text = open(guide).read()
split = []
sections = re.split(r"^### &", text, flags=re.M)[1:]
doc = {}
doc_defaults = {}
for sec in sections:
    name = sec.split()[0]
    keys = set()
    for row in re.findall(r"^\| (`[^|]*`) \|([^|]*)\|", sec, flags=re.M):
        row_keys = re.findall(r"`([a-z_0-9]+)`", row[0])
        keys.update(row_keys)
        if len(row_keys) == 1:
            # The guide's markup aside: `code` quotes, an em dash for '-'.
            doc_defaults[name, row_keys[0]] = row[1].strip().replace("`", "").replace("\u2014", "-")
    doc[name] = keys
    lines = sec.splitlines()
    rows = [i for i, line in enumerate(lines) if re.match(r"^\| `", line)]
    if rows and not all(line.startswith("|") for line in lines[rows[0]:rows[-1] + 1]):
        split.append(name)
for name in split:
    failed += 1
    print("FAIL &%s: its key table is split (a line that is not a table row between rows)"
          % name)
passed = 0
for group, keys in code.items():
    missing = keys - doc.get(group, set())
    extra = doc.get(group, set()) - keys
    wrong = sorted("%s: guide '%s', code '%s'" % (k, doc_defaults[group, k], defaults[group, k])
                   for k in keys if (group, k) in doc_defaults
                   and doc_defaults[group, k] != defaults[group, k])
    ok = not missing and not extra and not wrong
    failed += not ok
    passed += ok
    print(("PASS" if ok else "FAIL") + " &%s: %d keys" % (group, len(keys))
          + ("" if not (missing or extra) else " undocumented: %s; not in the code: %s"
             % (sorted(missing), sorted(extra)))
          + ("" if not wrong else "; defaults differ: " + "; ".join(wrong)))
print("%d passed, %d failed" % (passed, failed))
sys.exit(1 if failed or not code else 0)
