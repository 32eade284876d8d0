#!/usr/bin/env python3
"""Checks that the builds of this workspace resolve the same features for every dependency
they share, so that they share one compiled copy of it.

Cargo resolves features for the packages each command selects: `cargo test --workspace` (the
README's test command, with the tests' dev-dependencies), `cargo run --bin sylva` (the README's
first command: every member, no dev-dependencies) and maturin's build of crates/sylva-py alone.
Where one of them turns on a feature another does not, that dependency and everything above it
(often the whole engine) compiles twice. Exits non-zero naming each difference and who wants the
feature (`cargo tree -e features -i NAME` tells more)."""

import subprocess
import sys
from collections import defaultdict


def resolve(*args):
    out = subprocess.run(
        ["cargo", "tree", "--prefix", "none", "-f", "{p}|{f}", *args],
        check=True,
        capture_output=True,
        text=True,
    ).stdout
    features = defaultdict(set)
    for line in out.splitlines():
        if "|" not in line:
            continue
        package, feats = line.replace(" (*)", "").split("|", 1)
        package = package.split(" (")[0].strip()  # drop a member's path
        features[package].add(feats.strip())
    return features


tests = resolve("--workspace", "-e", "normal,build,dev")
builds = {
    "cargo run --bin sylva (every member, no dev-dependencies)": resolve("--workspace", "-e", "normal,build"),
    "maturin (crates/sylva-py alone)": resolve("-p", "sylva-py", "-e", "normal,build"),
}
failed = False
for name, resolved in builds.items():
    for package, sets in sorted(resolved.items()):
        # Each copy a build needs (a crate can be built once for build scripts and once for the
        # program, with different features) must be one the tests' build makes too.
        if package in tests and not sets <= tests[package]:
            failed = True
            print(f"{name}: {package} resolves to {sorted(sets)}, the tests' build to {sorted(tests[package])}")
if failed:
    print("\nName the missing features where the build that lacks them declares the dependency.")
    sys.exit(1)
print(f"one build: {len(tests)} packages resolve to the same features in the tests, the README's command and the wheel")
