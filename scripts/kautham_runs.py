"""What the benchmark scripts share: running the kautham command line and reading its JSON.

Standard library only; imported by scripts/benchmark-planners.py and
scripts/solve-and-validate.py (Python puts a script's own folder on its import path).
"""

import json
import os
import subprocess
import sys
import tempfile

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
KAUTHAM = os.environ.get("KAUTHAM", os.path.join(ROOT, "build", "apps", "kautham"))


def run(command):
    """Runs a command from the repository root, capturing its output."""
    return subprocess.run(command, cwd=ROOT, capture_output=True, text=True)


def validate(problem, plan_file, runs, seed, who):
    """`kautham validate --json`: the report as a dict (exits naming `who` if it fails)."""
    with tempfile.NamedTemporaryFile(suffix=".json", delete=False) as f:
        report = f.name
    result = run([KAUTHAM, "validate", problem, plan_file, "--runs", str(runs), "--seed",
                  str(seed), "--json", report])
    if result.returncode != 0:
        sys.exit(f"{who}: validate failed:\n{result.stderr}")
    with open(report) as f:
        data = json.load(f)
    os.unlink(report)
    return data
