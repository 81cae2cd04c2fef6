#!/usr/bin/env python3
# SPDX-License-Identifier: MIT
"""Runs every hostile-input case of model/tests/data/hostile/cli_cases.txt
through the built `pluecker` CLI and writes docs/hostile-input.md: per case
the input, the exit status and the message the program actually printed.

Nothing in the table is typed by hand: the status and message columns are
what this run observed; the last column compares them with the case's
expectation (the same one model/tests/test_hostile.cpp asserts).

  scripts/hostile_table.py [--cli build/model/pluecker] [--out docs/hostile-input.md]
                           [--timeout 20] [--mem-gib 4] [--check]

--check prints only the cases whose result differs from the expectation and
exits 1 if there are any. Without --check the table is written and the exit
status is 1 as well when a case differs (the table then shows it).
"""
import argparse
import os
import re
import resource
import shlex
import subprocess
import sys
import tempfile
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
DATA = ROOT / "model" / "tests" / "data"
HOSTILE = DATA / "hostile"
MANIFEST = HOSTILE / "cli_cases.txt"


def parse_manifest(path):
    cases, cur = [], None
    for raw in path.read_text().splitlines():
        line = raw.rstrip()
        if line.startswith("#"):
            continue
        if not line:
            cur = None
            continue
        key, _, value = line.partition(" ")
        if key == "case":
            cur = {"name": value, "args": [], "status": None, "expect": []}
            cases.append(cur)
        elif cur is None:
            raise SystemExit(f"{path}: '{line}' outside a case block")
        elif key == "args":
            cur["args"] = value.split()
        elif key == "status":
            cur["status"] = int(value)
        elif key == "expect":
            cur["expect"].append(value)
        else:
            raise SystemExit(f"{path}: unknown key '{key}'")
    return cases


def expand(arg, tmp):
    return arg.replace("{hostile}", str(HOSTILE)).replace("{data}", str(DATA)).replace("{tmp}", tmp)


def relative(text, tmp):
    text = text.replace(tmp, "$TMP")
    return text.replace(str(ROOT) + "/", "")


def run_case(cli, case, timeout, mem_gib):
    with tempfile.TemporaryDirectory(prefix="pluecker_hostile_") as tmp:
        argv = [cli] + [expand(a, tmp) for a in case["args"]]

        def limits():
            if mem_gib:
                lim = int(mem_gib * 2**30)
                resource.setrlimit(resource.RLIMIT_AS, (lim, lim))

        t0 = time.monotonic()
        try:
            p = subprocess.run(argv, capture_output=True, timeout=timeout, preexec_fn=limits, cwd=tmp)
            status, err = p.returncode, p.stderr.decode(errors="replace")
        except subprocess.TimeoutExpired as e:
            status, err = None, (e.stderr or b"").decode(errors="replace")
        secs = time.monotonic() - t0
        return status, relative(err, tmp), secs


def verdict(case, status, err):
    if status is None:
        return False
    if status != case["status"]:
        return False
    return all(e in err for e in case["expect"])


def md_cell(text, html=True, limit=200):
    text = text.replace("|", "\\|").replace("\n", " ")
    text = text if len(text) <= limit else text[:limit - 3] + "..."
    if html:  # outside code spans, <...> would be read as a tag
        text = text.replace("&", "&amp;").replace("<", "&lt;").replace(">", "&gt;")
    return text


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--cli", default=str(ROOT / "build" / "model" / "pluecker"))
    ap.add_argument("--out", default=str(ROOT / "docs" / "hostile-input.md"))
    ap.add_argument("--timeout", type=float, default=20.0, help="seconds per case")
    ap.add_argument("--mem-gib", type=float, default=4.0, help="address-space limit per case (0: none; use 0 for ASan builds)")
    ap.add_argument("--check", action="store_true", help="report mismatches only, write nothing")
    ap.add_argument("cases", nargs="*", help="run only these case names")
    a = ap.parse_args()

    cli = os.path.abspath(a.cli)
    if not os.access(cli, os.X_OK):
        raise SystemExit(f"hostile_table: {cli} not built (run 'make build')")
    cases = parse_manifest(MANIFEST)
    if a.cases:
        cases = [c for c in cases if c["name"] in a.cases]

    rows, bad = [], []
    for c in cases:
        status, err, secs = run_case(cli, c, a.timeout, a.mem_gib)
        ok = verdict(c, status, err)
        if not ok:
            bad.append((c, status, err))
        rows.append((c, status, err, secs, ok))
        if a.check and not ok:
            print(f"MISMATCH: {c['name']}: status {status}, expected {c['status']}: {err.strip()[:300]}")

    if not a.check:
        write_table(a.out, rows, a.timeout, a.mem_gib, cli)
        print(f"hostile_table: {len(rows)} cases, {sum(r[4] for r in rows)} as expected, "
              f"{len(bad)} unexpected; wrote {a.out}")
    for c, status, err in bad:
        print(f"hostile_table: UNEXPECTED {c['name']}: status {status}: {err.strip()[:300]}", file=sys.stderr)
    return 1 if bad else 0


def input_label(case):
    args = " ".join(case["args"])
    args = args.replace("{hostile}/", "").replace("{data}/", "").replace("{tmp}/", "$TMP/")
    args = re.sub(r" --size 4 --max-depth 0 --quiet --out \$TMP/out.png", " …", args)
    return "`pluecker " + args + "`" if args else "`pluecker`"


def write_table(out, rows, timeout, mem_gib, cli):
    sections = [
        ("Command-line flags", lambda c: not c["name"].startswith(("query_file_", "query_fixed_", "mesh_"))),
        ("Query files (`pluecker query`; the bad line is line 6 of each file)",
         lambda c: c["name"].startswith(("query_file_", "query_fixed_"))),
        ("Mesh files (`pluecker render --scene FILE --size 4 --max-depth 0 --quiet --out …`)",
         lambda c: c["name"].startswith("mesh_")),
    ]
    lines = [
        "<!-- SPDX-License-Identifier: MIT -->",
        "<!-- Generated by scripts/hostile_table.py from model/tests/data/hostile/cli_cases.txt; do not edit. -->",
        "# Hostile input: what each case gets",
        "",
        "Every row is a real run of the `pluecker` CLI (`" + os.path.relpath(cli, ROOT) + "`) on a hostile input.",
        "*Status* and *message* are what that run printed (first line of standard error;",
        "paths relative to the repository). Exit status 2 means bad input or options,",
        "0 means the input was accepted, 1 an internal error. Each run had a limit of",
        f"{timeout:g} s and {'%g GiB of address space' % mem_gib if mem_gib else 'no memory limit'};",
        "*timeout* means the limit was hit.",
        "*Result* compares the run with the case's expectation, which",
        "`model/tests/test_hostile.cpp` asserts in `make test` (every case, none skipped):",
        "**ok**, or **differs** when the run did not give the expected status and message.",
        "Input files are in `model/tests/data/hostile/`.",
        "",
        "Regenerate: `make hostile-table` (builds the CLI, then runs every case in a few seconds).",
        "How the cases are found and kept: libFuzzer targets in `model/fuzz/` (`make fuzz`),",
        "every finding becomes a file here and a case in `cli_cases.txt`; the whole test",
        "suite also runs under ASan + UBSan (`make test-sanitize`).",
        "",
    ]
    for title, pred in sections:
        sel = [r for r in rows if pred(r[0])]
        if not sel:
            continue
        lines += [f"## {title}", "", "| Case | Input | Status | Message | Result |", "|---|---|---|---|---|"]
        for c, status, err, secs, ok in sel:
            first = err.strip().splitlines()[0] if err.strip() else ""
            st = "timeout" if status is None else str(status)
            if status is None:
                first = f"(no answer within {timeout:g} s) " + first
            elif status == 0 and not first:
                first = "(accepted: exit 0, nothing on standard error)"
            res = "ok" if ok else f"**differs** (expected status {c['status']})"
            lines.append(f"| {c['name']} | {md_cell(input_label(c), html=False)} | {st} | {md_cell(first)} | {md_cell(res, limit=400)} |")
        lines.append("")
    Path(out).parent.mkdir(parents=True, exist_ok=True)
    Path(out).write_text("\n".join(lines))


if __name__ == "__main__":
    sys.exit(main())
