"""The release `robowire` binary the bench scripts run: the one given, or one
built here with the features they need. Stdlib only."""

import os
import subprocess

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))


def release_binary(given, features):
    """`given` if set, else build `--release --features FEATURES` and return
    its path (in $CARGO_TARGET_DIR, default target/)."""
    if given is not None:
        return given
    subprocess.run(
        ["cargo", "build", "--release", "--features", features, "--bin", "robowire"],
        cwd=ROOT,
        check=True,
    )
    target = os.environ.get("CARGO_TARGET_DIR", os.path.join(ROOT, "target"))
    return os.path.join(ROOT, target, "release", "robowire")
