#!/usr/bin/env python3
"""Check that every dependency of the library, with all features, resolves to
a version whose rust-version is at most the MSRV, the way cargo's MSRV-aware
resolver picks them for a user on that Rust. Run from a scratch copy of the
crate: it rewrites Cargo.lock.

A feature documented with its own, newer MSRV (cli-foxglove: the foxglove
crate needs Rust 1.88) is checked against that one instead, and the other
features are checked without it."""

import json
import os
import subprocess
import sys


def version(text):
    parts = [int(x) for x in text.split(".")[:3]]
    return tuple(parts + [0] * (3 - len(parts)))


def cargo(*args, **env):
    return subprocess.run(
        ["cargo", *args],
        capture_output=True,
        text=True,
        check=True,
        env={**os.environ, **env},
    ).stdout


# Features whose dependencies need a newer Rust than the crate's MSRV, as the
# README's feature table and docs/cli.md say.
OWN_MSRV = {"cli-foxglove": "1.88"}


def check(msrv, features):
    """The dependencies too new for `msrv` with `features` on."""
    tree = cargo("tree", "-e", "normal,build", "--features", ",".join(features),
                 "--prefix", "none", "--format", "{p}")
    used = {tuple(line.split()[:2]) for line in tree.splitlines() if line.strip()}
    meta = json.loads(cargo("metadata", "--format-version", "1", "--all-features"))
    too_new = []
    for package in sorted(meta["packages"], key=lambda p: p["name"]):
        if (package["name"], "v" + package["version"]) not in used:
            continue
        needs = package.get("rust_version")
        print(f'{package["name"]:20} {package["version"]:10} rust-version {needs or "-"}')
        if needs and version(needs) > version(msrv):
            too_new.append(f'{package["name"]} {package["version"]} needs Rust {needs}')
    return too_new


def main():
    msrv = sys.argv[1]
    cargo("generate-lockfile", CARGO_RESOLVER_INCOMPATIBLE_RUST_VERSIONS="fallback")
    meta = json.loads(cargo("metadata", "--format-version", "1", "--no-deps"))
    features = [f for f in meta["packages"][0]["features"] if f != "default"]
    too_new = check(msrv, [f for f in features if f not in OWN_MSRV])
    for feature, own in OWN_MSRV.items():
        too_new += [f"{feature}: {t}" for t in check(own, [feature])]
    if too_new:
        sys.exit(f"needs a newer Rust than {msrv} (or the feature's own):\n  " + "\n  ".join(too_new))
    print(f"every dependency of every feature builds with Rust {msrv}; " +
          ", ".join(f"{f} with Rust {v}" for f, v in OWN_MSRV.items()))


if __name__ == "__main__":
    main()
