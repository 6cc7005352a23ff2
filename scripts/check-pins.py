#!/usr/bin/env python3
"""Each crate built alone resolves its dependencies' features as the whole workspace does.

`cargo test -p <crate>` (the mutation check, scripts/mutations.py) resolves features over that
crate alone; where they differ from the workspace's (`cargo test` at the root, the tests stage),
cargo builds those dependencies a second time, and every crate that depends on them: 160–290 s
for each crate's first mutation in CI before crates/pins existed. This compares `cargo tree`'s
features, crate by crate, with the workspace's and lists what crates/pins/Cargo.toml must pin.

Usage: python3 scripts/check-pins.py    (a few seconds; exit 1 if a crate differs)
"""
import subprocess
import sys

CRATES = ['catena-seabed', 'catena-fe', 'catena', 'catena-io', 'catena-cli']
# Host-only instances (toml's, used by a build script in the workspace) merge with the target's in
# `cargo tree`'s listing; these differ only there.
HOST_ONLY = {'toml_datetime', 'toml_parser', 'winnow'}


def features(pkg=None):
    cmd = ['cargo', 'tree', '--locked', '-e', 'normal,build,dev', '--prefix', 'none',
           '-f', '{p}|{f}']
    if pkg:
        cmd += ['-p', pkg]
    out = subprocess.run(cmd, capture_output=True, text=True, check=True).stdout
    d = {}
    for line in out.splitlines():
        line = line.replace(' (*)', '').strip()
        if '|' not in line:
            continue
        p, f = line.split('|', 1)
        name = ' '.join(p.split()[:2])
        d.setdefault(name, set()).update(x for x in f.split(',') if x)
    return d


def main():
    ws = features()
    bad = []
    for pkg in CRATES:
        for name, f in sorted(features(pkg).items()):
            if name.split()[0] in HOST_ONLY:
                continue
            if f != ws.get(name, set()):
                bad.append(f'{pkg}: {name}: the workspace adds {sorted(ws.get(name, set()) - f)}')
    if bad:
        print('\n'.join(bad))
        sys.exit('pin these features in crates/pins/Cargo.toml (each crate must build its '
                 'dependencies as the workspace does)')
    print(f'{len(CRATES)} crates, each resolves its dependencies as the workspace does')


if __name__ == '__main__':
    main()
