"""The headline numbers of every shipped scene and of `formopt compare` on the real trials, as
one JSON: run it before and after a refactor and diff the two files.

    python benchmarks/regression.py out/before.json
    python benchmarks/regression.py out/after.json --compare out/before.json

Per scene: `formopt stride` (stride scenes), `formopt impact` (every other scene), `formopt simulate` (scenes with [landing]) and
`formopt solve` (scenes with [optimize]) through their --json reports; per trial: the compare
table's rows (`formopt compare --scene problems/compare/runners.toml --json`). Numbers that
differ by more than 1e-6 relative are listed with `--compare`.
"""

from __future__ import annotations

import argparse
import json
import subprocess
import sys
import tomllib
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]


def run(*args) -> dict:
    """The --json report of one formopt command (exit status and stderr kept on failure)."""
    cmd = [sys.executable, "-m", "formopt.cli", *args, "--json"]
    done = subprocess.run(cmd, cwd=ROOT, capture_output=True, text=True)
    if done.returncode != 0:
        return {"exit": done.returncode, "stderr": done.stderr.strip()[-300:]}
    text = done.stdout
    start = text.find("\n{") + 1 if not text.startswith("{") else 0  # compare prints tables first
    return json.loads(text[start:])


def numbers(data, prefix="") -> dict[str, float]:
    """Every number in a JSON tree, keyed by its path (strings and booleans as text)."""
    out: dict[str, float] = {}
    if isinstance(data, dict):
        for k, v in data.items():
            out.update(numbers(v, f"{prefix}.{k}" if prefix else str(k)))
    elif isinstance(data, list):
        for k, v in enumerate(data):
            out.update(numbers(v, f"{prefix}[{k}]"))
    elif isinstance(data, (bool, str)) or data is None:
        out[prefix] = str(data)
    elif isinstance(data, (int, float)):
        out[prefix] = float(data)
    return out


def collect() -> dict:
    report = {}
    for scene in sorted((ROOT / "formopt" / "scenes").glob("*.toml")):
        tables = tomllib.loads(scene.read_text())
        rel = str(scene.relative_to(ROOT))
        if "stride" in tables:  # a stride scene has no touchdown: its own command
            report[f"stride {rel}"] = run("stride", rel, "--out", str(ROOT / "out/regression"))
            continue
        report[f"impact {rel}"] = run("impact", rel)
        if "landing" in tables:
            report[f"simulate {rel}"] = run("simulate", rel, "--out", str(ROOT / "out/regression"))
        if "optimize" in tables:
            report[f"solve {rel}"] = run("solve", rel, "--out", str(ROOT / "out/regression"))
        print(f"{rel} done", file=sys.stderr)
    out = ROOT / "out/regression"
    report["compare runners"] = run("compare", "--scene", "problems/compare/runners.toml",
                                    "--out", str(out))
    for path in sorted(out.glob("*/comparison.json")):  # each trial's full report
        report[f"compare {path.parent.name}"] = json.loads(path.read_text())
    return report


SKIP = ("solve_s", "seconds", "time_s", "files", "elapsed", "build_s")


def differences(before: dict, after: dict, rtol: float = 1e-6) -> list[str]:
    a, b = numbers(before), numbers(after)
    out = []
    for key in sorted(set(a) | set(b)):
        if any(s in key for s in SKIP):
            continue
        x, y = a.get(key), b.get(key)
        if isinstance(x, float) and isinstance(y, float):
            if abs(x - y) > rtol * max(abs(x), abs(y), 1e-9):
                out.append(f"{key}: {x:.9g} -> {y:.9g}")
        elif x != y:
            out.append(f"{key}: {x} -> {y}")
    return out


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("out", type=Path)
    parser.add_argument("--compare", type=Path, help="an earlier output to diff against")
    args = parser.parse_args()
    report = collect()
    args.out.parent.mkdir(parents=True, exist_ok=True)
    args.out.write_text(json.dumps(report, indent=1, default=str))
    if args.compare:
        diff = differences(json.loads(args.compare.read_text()), report)
        print("\n".join(diff) if diff else "no number changed")
        print(f"{len(diff)} differences", file=sys.stderr)


if __name__ == "__main__":
    main()
