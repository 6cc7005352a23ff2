#!/usr/bin/env python3
"""The safety net's mutation check (validation/safety-net.md).

Each mutation in `scripts/mutations.toml` is a deliberate bug anchored to the code it breaks: one or
more edits, each an exact text that must occur exactly once in its file. The check

1. verifies that every anchor still applies (a mutation whose text is no longer in the code is an
   error, never a skip: when the code moves, the mutation moves with it);
2. makes each mutation alone, in place, builds the test targets it names and runs the tests it names
   (`package:target:test`, target `lib` for unit tests), and restores the file whatever happens;
3. fails unless every mutation compiles and at least one of its tests fails on it (a mutation that
   does not compile tests nothing and is an error too).

Only the named tests run, so a mutation costs one release build of the crate it touches, of those
above it and of its test target, not the whole suite: CI runs this with CARGO_INCREMENTAL=1, a few
seconds to a quarter of a minute a mutation on 2 cores once each crate's first has built it
(crates/pins keeps `cargo test -p <crate>` on the workspace's build of the dependencies).

Usage:
    python3 scripts/mutations.py [--check] [--write-doc] [NAME ...]
    python3 scripts/mutations.py --doc-from LOG
      --check      only verify that every anchor applies (seconds)
      --write-doc  rewrite the table in validation/safety-net.md from this run
      --doc-from   rewrite that table from the lines a whole run printed (CI's log): every
                   mutation of scripts/mutations.toml must have its line there, caught
"""
import argparse
import json
import os
import re
import subprocess
import sys
import time
import tomllib

REPO = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
SPEC = os.path.join(REPO, 'scripts', 'mutations.toml')
DOC = os.path.join(REPO, 'validation', 'safety-net.md')
BEGIN, END = '<!-- mutations:begin -->', '<!-- mutations:end -->'


def load():
    with open(SPEC, 'rb') as f:
        spec = tomllib.load(f)
    muts = spec.get('mutation', [])
    names = [m['name'] for m in muts]
    dup = {n for n in names if names.count(n) > 1}
    if dup:
        sys.exit(f'{SPEC}: mutation names repeated: {sorted(dup)}')
    for m in muts:
        for key in ('name', 'what', 'edit', 'tests'):
            if key not in m:
                sys.exit(f'{SPEC}: mutation {m.get("name", "?")!r} has no {key!r}')
        for t in m['tests']:
            if len(t.split(':', 2)) != 3 or not all(t.split(':', 2)):
                sys.exit(f'{SPEC}: mutation {m["name"]!r}: test {t!r} is not package:target:test')
    return muts


def anchor_problems(m):
    """Why the mutation no longer applies (empty when every edit's text occurs exactly once)."""
    out = []
    for e in m['edit']:
        path = os.path.join(REPO, e['file'])
        if not os.path.exists(path):
            out.append(f'{e["file"]}: no such file')
            continue
        n = open(path).read().count(e['find'])
        if n != 1:
            out.append(f'{e["file"]}: the text to replace occurs {n} times (expected once):\n'
                       + '\n'.join('      | ' + l for l in e['find'].splitlines()))
        if e['find'] == e['replace']:
            out.append(f'{e["file"]}: the replacement is the text itself')
    return out


def groups(tests):
    """{(package, target): [test, ...]} in the order given."""
    g = {}
    for t in tests:
        pkg, target, name = t.split(':', 2)
        g.setdefault((pkg, target), []).append(name)
    return g


def run_mutation(m):
    originals = {}
    try:
        for e in m['edit']:
            path = os.path.join(REPO, e['file'])
            originals.setdefault(path, open(path).read())
            cur = open(path).read()
            open(path, 'w').write(cur.replace(e['find'], e['replace'], 1))
        failed, problems = [], []
        for (pkg, target), names in groups(m['tests']).items():
            sel = ['--lib'] if target == 'lib' else ['--test', target]
            cmd = ['cargo', 'test', '--release', '-p', pkg, *sel, '--', '--exact', *names]
            r = subprocess.run(cmd, cwd=REPO, capture_output=True, text=True)
            out = r.stdout + r.stderr
            if 'error[E' in out or 'could not compile' in out:
                problems.append(f'does not compile ({" ".join(cmd)}):\n' + out[-3000:])
                continue
            ran = re.findall(r'^test (\S+) \.\.\. (ok|FAILED|ignored)', out, re.M)
            missing = [n for n in names if n not in {t for t, _ in ran}]
            if missing:
                problems.append(f'{pkg}:{target}: no such test(s) ran: {missing}')
            failed += [f'{pkg}:{target}:{t}' for t, s in ran if s == 'FAILED']
        return failed, problems
    finally:
        for path, text in originals.items():
            open(path, 'w').write(text)


def write_doc(rows):
    doc = open(DOC).read()
    if BEGIN not in doc or END not in doc:
        sys.exit(f'{DOC}: the markers {BEGIN} / {END} are missing')
    lines = ['| mutation | what it breaks | where | tests that catch it | s |', '|---|---|---|---|---|']
    for m, failed, secs in rows:
        where = ', '.join(sorted({f'`{e["file"]}`' for e in m['edit']}))
        caught = ', '.join(f'`{t.split(":", 2)[2]}` ({t.split(":", 2)[1]})' for t in failed)
        lines.append(f'| `{m["name"]}` | {m["what"]} | {where} | {caught} | {secs:.0f} |')
    head, rest = doc.split(BEGIN, 1)
    _, tail = rest.split(END, 1)
    open(DOC, 'w').write(head + BEGIN + '\n' + '\n'.join(lines) + '\n' + END + tail)


def rows_from_log(path, muts):
    """The table's rows from the JSON lines a whole run printed in `path` (the last line of each
    mutation counts); every mutation must be there and caught."""
    seen = {}
    with open(path) as f:
        for line in f:
            if line.startswith('{"mutation"'):
                r = json.loads(line)
                seen[r['mutation']] = r
    missing = [m['name'] for m in muts if m['name'] not in seen]
    if missing:
        sys.exit(f'{path}: no line for {", ".join(missing)}')
    uncaught = [m['name'] for m in muts if not seen[m['name']]['caught_by'] or seen[m['name']]['problems']]
    if uncaught:
        sys.exit(f'{path}: not caught (or broken) there: {", ".join(uncaught)}')
    return [(m, seen[m['name']]['caught_by'], seen[m['name']]['seconds']) for m in muts]


def main():
    ap = argparse.ArgumentParser(description=__doc__.split('\n')[0])
    ap.add_argument('--check', action='store_true')
    ap.add_argument('--write-doc', action='store_true')
    ap.add_argument('--doc-from', metavar='LOG')
    ap.add_argument('names', nargs='*')
    a = ap.parse_args()
    muts = load()
    if a.doc_from:
        write_doc(rows_from_log(a.doc_from, muts))
        return
    known = {m['name'] for m in muts}
    unknown = [n for n in a.names if n not in known]
    if unknown:
        sys.exit(f'unknown mutation(s): {unknown}; known: {sorted(known)}')
    chosen = [m for m in muts if not a.names or m['name'] in a.names]
    stale = {m['name']: p for m in chosen if (p := anchor_problems(m))}
    for name, ps in stale.items():
        print(f'mutation {name!r} no longer applies:', file=sys.stderr)
        for p in ps:
            print('  ' + p, file=sys.stderr)
    if stale:
        sys.exit(f'{len(stale)} mutation(s) no longer apply: update scripts/mutations.toml with the code')
    print(f'{len(chosen)} mutations, every anchor applies', flush=True)
    if a.check:
        return
    rows, bad = [], []
    for m in chosen:
        t0 = time.time()
        failed, problems = run_mutation(m)
        secs = time.time() - t0
        print(json.dumps({'mutation': m['name'], 'caught_by': failed, 'seconds': round(secs),
                          'problems': problems}), flush=True)
        if problems or not failed:
            bad.append(m['name'])
        rows.append((m, failed, secs))
    if a.write_doc and not bad and not a.names:
        write_doc(rows)
    if bad:
        sys.exit(f'mutations not caught (or broken): {", ".join(bad)}')
    print(f'{len(chosen)} mutations, every one caught')


if __name__ == '__main__':
    main()
