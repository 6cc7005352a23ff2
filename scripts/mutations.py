#!/usr/bin/env python3
"""The safety net's mutation check (validation/safety-net.md): makes each deliberate bug in turn in a
throw-away git worktree of HEAD, runs the whole test suite there, and prints one JSON line per
mutation with the tests that failed. Every mutation must fail at least one test.

Usage: python3 scripts/mutations.py [NAME ...]   (about 3 minutes per mutation on 2 cores)
"""
import sys, subprocess, re, json, tempfile, os
repo = subprocess.run(['git', 'rev-parse', '--show-toplevel'], capture_output=True, text=True, check=True).stdout.strip()
tmp = tempfile.mkdtemp(prefix='catena-mutants-')
root = os.path.join(tmp, 'tree')
subprocess.run(['git', 'worktree', 'add', '-q', '--detach', root, 'HEAD'], cwd=repo, check=True)
D='crates/fe/src/dynamics.rs'; S='crates/fe/src/assembly.rs'; E='crates/fe/src/environment.rs'
muts = {
 'flip-alpha': [(D, "ws.g[e] = inertia[k] + (1.0 + alpha) * ws.f[g] - alpha * state.f_prev[g];",
                   "ws.g[e] = inertia[k] + (1.0 - alpha) * ws.f[g] + alpha * state.f_prev[g];")],
 'zero-added-mass': [(D, "let ma = h.added_mass(model.node_od[i], model.tributary[i]);", "let ma = 0.0 * h.added_mass(model.node_od[i], model.tributary[i]);")],
 'drop-drag': [(E, "let kn0 = 0.5 * self.water_density * self.cd_normal;", "let kn0 = 0.0 * self.water_density * self.cd_normal;"),
               (E, "let ka0 = 0.5 * self.water_density * self.cd_axial * std::f64::consts::PI;", "let ka0 = 0.0 * self.water_density * self.cd_axial * std::f64::consts::PI;")],
 'commit-every-iterate': [(D, """        forces_at_iterate(dm, &state.history, ws, !reuse, 1.0 + alpha, c_v, dt);""", """        forces_at_iterate(dm, &state.history, ws, !reuse, 1.0 + alpha, c_v, dt);
        state.history.copy_from_slice(&ws.next);""")],
 'top-at-t-plus-alpha-dt': [(D, "let prescribed = dm.motion.as_ref().map(|m| m.at(t1));", "let prescribed = dm.motion.as_ref().map(|m| m.at(t1 + alpha * dt));")],
 'flexjoint-sign': [(S, "self.residual[g] += fj.stiffness * (q[g] + u[g] - fj.neutral);", "self.residual[g] -= fj.stiffness * (q[g] + u[g] - fj.neutral);"),
                    (S, "self.k.values[self.diag_slots[eq]] += fj.stiffness;", "self.k.values[self.diag_slots[eq]] -= fj.stiffness;")],
}
names = sys.argv[1:] or list(muts)
survivors = []
for name in names:
    subprocess.run(['git','checkout','-q','--','.'], cwd=root, check=True)
    for f, a, b in muts[name]:
        p = f'{root}/{f}'; s = open(p).read()
        assert s.count(a) == 1, (name, a)
        open(p,'w').write(s.replace(a,b))
    r = subprocess.run('cargo test --release --workspace --all-targets --no-fail-fast 2>&1', shell=True, cwd=root, capture_output=True, text=True)
    failed = re.findall(r'^test (\S+) \.\.\. FAILED', r.stdout, re.M)
    # failing test binaries
    bins = re.findall(r'error: test failed, to rerun pass `([^`]*)`', r.stdout)
    print(json.dumps({'mutation': name, 'failed': failed, 'bins': bins}), flush=True)
    if not failed:
        survivors.append(name)
subprocess.run(['git','checkout','-q','--','.'], cwd=root, check=True)
subprocess.run(['git', 'worktree', 'remove', '--force', root], cwd=repo)
if survivors:
    print('mutations no test caught: ' + ', '.join(survivors))
    sys.exit(1)
