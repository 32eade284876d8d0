#!/usr/bin/env python3
"""Lists the test executables of a cargo build, from `cargo test --no-run
--message-format=json` on stdin: one line each of package, target, folder to run it in,
executable. .ci/run reruns test binaries of the one workspace build under other drivers this
way: `cargo test -p X` would resolve features for X alone and compile much of the engine again."""

import json
import os
import sys

for line in sys.stdin:
    if not line.startswith("{"):
        continue
    m = json.loads(line)
    if m.get("reason") != "compiler-artifact" or not m.get("executable"):
        continue
    if not m["profile"]["test"]:
        continue
    package = os.path.basename(os.path.dirname(m["manifest_path"]))
    print(package, m["target"]["name"], os.path.dirname(m["manifest_path"]), m["executable"])
