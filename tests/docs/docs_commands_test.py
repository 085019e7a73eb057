#!/usr/bin/env python3
"""ctest `docs-commands`: the user docs' quick commands run as written.

Every fenced block that opens with ```sh in README.md and docs/*.md (not
docs/design/ or docs/journal/) is run, in document order, one bash session
per document, in a scratch folder where assets/, demos/, python/ and scripts/
are the source tree's and build/ is the build folder; out/ and docs/gallery/
are the scratch folder's own. Blocks opened with ```console are shown to the
reader only: commands that install, build, open a window, take minutes or
need the reader's own files (DEVELOPERS.md, "Docs"). A command that fails
fails the test, naming the document, the line and the output.

Then the numbers docs/PYTHON.md quotes are compared with what its commands
printed, within the printed precision.

    docs_commands_test.py SOURCE_DIR BUILD_DIR
"""
import os
import pathlib
import re
import subprocess
import sys
import tempfile
import time


def user_docs(source):
    docs = [source / "README.md"] + sorted((source / "docs").glob("*.md"))
    return [d for d in docs if d.is_file()]


def quick_commands(doc):
    """(line number, command) of every command in the doc's ```sh blocks,
    continuation lines joined; comments and blank lines dropped."""
    commands, in_block, run_block, pending, start = [], False, False, [], 0
    for number, line in enumerate(doc.read_text().splitlines(), 1):
        stripped = line.strip()
        if stripped.startswith("```"):
            if not in_block:
                in_block, run_block = True, stripped[3:].strip() == "sh"
            else:
                in_block = False
            continue
        if not (in_block and run_block):
            continue
        if not pending:
            if not stripped or stripped.startswith("#"):
                continue
            start = number
        pending.append(line)
        if not line.rstrip().endswith("\\"):
            commands.append((start, "\n".join(pending)))
            pending = []
    return commands


def make_scratch(source, build, scratch):
    for name in ("assets", "demos", "python", "scripts", "examples"):
        (scratch / name).symlink_to(source / name)
    (scratch / "build").symlink_to(build)
    (scratch / "out").mkdir()
    (scratch / "docs" / "gallery").mkdir(parents=True)


def run_doc(doc, commands, scratch, logs):
    """Runs the commands in one bash session; returns [(line, command, rc, seconds, output)]."""
    script = ["set -o pipefail", f"cd {scratch}"]
    for k, (line, command) in enumerate(commands):
        log = logs / f"{k}.log"
        script += ["__start=$EPOCHREALTIME",
                   "{", command, f"}} >{log} 2>&1",
                   "__rc=$?",
                   f"echo \"@@ {k} $__rc $__start $EPOCHREALTIME\"",
                   "[ $__rc -eq 0 ] || exit 1"]
    env = dict(os.environ)
    env["PATH"] = f"{scratch / 'build'}:{env['PATH']}"
    done = subprocess.run(["bash", "-c", "\n".join(script)], env=env, capture_output=True, text=True)
    results = []
    for m in re.finditer(r"^@@ (\d+) (\d+) ([0-9.]+) ([0-9.]+)$", done.stdout, re.M):
        k, rc, seconds = int(m.group(1)), int(m.group(2)), float(m.group(4)) - float(m.group(3))
        line, command = commands[k]
        results.append((line, command, rc, seconds, (logs / f"{k}.log").read_text(errors="replace")))
    if done.returncode != 0 and (not results or results[-1][2] == 0):
        results.append((0, "(the session)", done.returncode, 0.0, done.stdout + done.stderr))
    return results


def table_rows(text):
    """{K: [the table's numbers as printed]} for each | K | ... | row of a markdown or printed table."""
    rows = {}
    for m in re.finditer(r"^\|\s*(\d+)\s*\|(.*)\|\s*$", text, re.M):
        rows[int(m.group(1))] = [cell.strip() for cell in m.group(2).split("|")]
    return rows


def tables_by_environment(text):
    """{environment file: table_rows} for the tables of docs/PYTHON.md (each under a
    line that starts with the file's name) and of error_vs_k.py (each under its
    "environment NAME.exr" line)."""
    tables, name = {}, None
    for line in text.splitlines():
        m = re.match(r"^(\w+\.exr) ", line) or re.search(r"environment (\w+\.exr)", line)
        if m:
            name = m.group(1)
            tables.setdefault(name, {})
        elif name:
            tables[name].update(table_rows(line))
    return tables


def agree(quoted, printed):
    """Whether the doc's number equals the printed one within the doc's last digit."""
    digits = len(quoted.split(".")[1]) if "." in quoted else 0
    return abs(float(quoted) - float(printed)) <= 1.01 * 10 ** -digits


def check_python_numbers(source, outputs):
    failures = []
    doc = (source / "docs" / "PYTHON.md").read_text()
    printed = next((out for command, out in outputs if "error_vs_k.py" in command), None)
    if printed is None:
        return ["docs/PYTHON.md: error_vs_k.py did not run"]
    quoted, measured = tables_by_environment(doc), tables_by_environment(printed)
    if len(quoted) != 3:
        failures.append(f"docs/PYTHON.md: {len(quoted)} tables found, expected 3")
    for environment, rows in quoted.items():
        for k, cells in rows.items():
            got = measured.get(environment, {}).get(k)
            if got is None:
                failures.append(f"docs/PYTHON.md: {environment} K = {k}: error_vs_k.py printed no such row")
                continue
            # The error columns; the shading times are the machine's, not checked.
            for column, (a, b) in enumerate(zip(cells[:4], got[:4])):
                if not agree(a, b):
                    failures.append(f"docs/PYTHON.md: {environment} K = {k}, column {column + 2}: "
                                    f"the doc says {a}, error_vs_k.py printed {b}")
    m = re.search(r"on a floor, ([\d,]+) vertices", doc)
    v = re.search(r"([\d,]+) vertices", printed)
    if not m or not v or m.group(1).replace(",", "") != v.group(1).replace(",", ""):
        failures.append(f"docs/PYTHON.md: the doc says {m and m.group(1)} vertices, error_vs_k.py printed {v and v.group(1)}")
    return failures


def main():
    source, build = pathlib.Path(sys.argv[1]).resolve(), pathlib.Path(sys.argv[2]).resolve()
    failures, outputs, total = [], [], 0.0
    with tempfile.TemporaryDirectory(prefix="rsl-docs-") as work:
        scratch = pathlib.Path(work) / "clone"
        scratch.mkdir()
        make_scratch(source, build, scratch)
        for doc in user_docs(source):
            commands = quick_commands(doc)
            if not commands:
                continue
            name = doc.relative_to(source)
            logs = pathlib.Path(work) / f"logs-{doc.stem}"
            logs.mkdir()
            for line, command, rc, seconds, output in run_doc(doc, commands, scratch, logs):
                total += seconds
                first = command.splitlines()[0]
                print(f"{name}:{line}: {seconds:5.1f} s  {first}")
                outputs.append((command, output))
                if rc != 0:
                    failures.append(f"{name}:{line}: `{command}` exited with {rc}:\n{output[-3000:]}")
    failures += check_python_numbers(source, outputs)
    print(f"{len(outputs)} commands in {total:.1f} s")
    for f in failures:
        print("FAIL: " + f, file=sys.stderr)
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
