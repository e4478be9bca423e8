#!/usr/bin/env python3
"""Every physics term meltdemFoam registers (meltdemFoam -listTerms) is one folder
foam-src/meltdemModels/terms/<name>/ with its source (<name>Term.H/.C), its doc (README.md, which
names the switches the term needs as the solver declares them) and its test (test_<name>.py);
and every such folder is a registered term."""
import json
import os
import re
import subprocess
import sys

from meltdem import paths
from meltdem.testing.report import check_absolute

TEST = "foam.terms.complete"
out = subprocess.run([paths.binary("meltdemFoam"), "-listTerms"], capture_output=True, text=True,
                     env=paths.tool_env()).stdout
table = json.loads(out[out.index("{"):])["terms"]
folder = os.path.join(paths.source_dir(), "foam-src", "meltdemModels", "terms")
folders = sorted(d for d in os.listdir(folder) if os.path.isdir(os.path.join(folder, d)))
unhoused = sorted(set(table) - set(folders))
ok = check_absolute(TEST, f"registered terms without a folder ({', '.join(unhoused) or 'none'})", len(unhoused), 0, 0)
ok &= check_absolute(TEST, f"term folders not registered ({', '.join(sorted(set(folders) - set(table))) or 'none'})",
                     len(set(folders) - set(table)), 0, 0)
incomplete = []
for name in sorted(set(table) & set(folders)):
    d = os.path.join(folder, name)
    wanted = [f"{name}Term.H", f"{name}Term.C", "README.md", f"test_{name}.py"]
    missing = [f for f in wanted if not os.path.isfile(os.path.join(d, f))]
    if missing:
        incomplete.append(f"{name}: {' '.join(missing)}")
        continue
    readme = open(os.path.join(d, "README.md")).read()
    m = re.search(r"^\| switch \| `physics \{ (\w+) on; \}`(?:, needs (.*?))? \|$", readme, re.M)
    needs = sorted(re.findall(r"`(\w+)`", m.group(2) or "")) if m else None
    if m is None or m.group(1) != name or needs != sorted(table[name]["needs"]):
        incomplete.append(f"{name}: README switch row says {needs}, the solver needs {sorted(table[name]['needs'])}")
ok &= check_absolute(TEST, f"terms without source, README, test or with a README that misstates their needs "
                     f"({'; '.join(incomplete) or 'none'})", len(incomplete), 0, 0)
sys.exit(0 if ok else 1)
