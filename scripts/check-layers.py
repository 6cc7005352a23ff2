#!/usr/bin/env python3
"""Fails when the modules of a crate import each other in a cycle.

For each crate under crates/, every `crate::m` (and, in a submodule, `super::m`) reference outside
comments is an edge from the file's top-level module to `m`; a cycle among top-level modules is
reported and the script exits 1. (Crates themselves cannot form cycles: cargo refuses them.)

A crate whose folders are its layers declares their order in LAYERS, lowest first: a top-level
module may then use only itself and the modules before it (`error`, shared by all, comes first),
and a top-level module missing from the list fails the check, so a new folder has to take its
place in the order.
"""
import os,re,sys,itertools
root=os.path.join(os.path.dirname(os.path.abspath(__file__)),'..','crates')
# The layers of the library, lowest first (ARCHITECTURE.md, crates/app/src/lib.rs).
LAYERS={'app':['error','checks','scene','run','studies']}
bad=0
for crate in sorted(os.listdir(root)):
    src=os.path.join(root,crate,'src')
    mods={}
    for dp,_,fs in os.walk(src):
        for f in fs:
            if not f.endswith('.rs'): continue
            p=os.path.join(dp,f); rel=os.path.relpath(p,src)[:-3].replace(os.sep,'::')
            rel=rel.replace('::mod','')
            if rel in ('lib','main'): continue
            top=rel.split('::')[0]
            txt='\n'.join(l for l in open(p).read().splitlines() if not l.strip().startswith('//'))
            deps=set(m for m in re.findall(r'crate::([a-z_]+)',txt))
            deps|=set(m for m in re.findall(r'super::([a-z_]+)',txt) if '::' in rel)
            mods.setdefault(top,set()).update(d for d in deps if d!=top)
    # find cycles among top-level modules
    def dfs(n,stack,seen):
        global bad
        for d in mods.get(n,()):
            if d in stack:
                print(crate,'cycle:',' -> '.join(stack[stack.index(d):]+[d])); bad+=1
            elif d not in seen:
                seen.add(d); dfs(d,stack+[d],seen)
    for m in mods: dfs(m,[m],{m})
    order=LAYERS.get(crate)
    if order:
        for m,deps in sorted(mods.items()):
            if m not in order:
                print(crate,'module',m,'is in no layer: add it to LAYERS in scripts/check-layers.py'); bad+=1
                continue
            for d in sorted(deps):
                if d in order and order.index(d)>order.index(m):
                    print(crate,'layer:',m,'uses',d,'which is above it'); bad+=1
print('check-layers: ' + ('%d problems' % bad if bad else 'no import cycle between modules, every layer uses only those below it'))
sys.exit(1 if bad else 0)
