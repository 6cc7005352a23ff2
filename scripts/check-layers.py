#!/usr/bin/env python3
"""Fails when the modules of a crate import each other in a cycle.

For each crate under crates/, every `crate::m` (and, in a submodule, `super::m`) reference outside
comments is an edge from the file's top-level module to `m`; a cycle among top-level modules is
reported and the script exits 1. (Crates themselves cannot form cycles: cargo refuses them.)

The same holds between files: a file's `crate::a::b`, `super::x` and `self::x` paths (braced
`use` lists included) are edges to the files of the modules they name, and two files of one crate
that reach each other (`dynamics/pair.rs` and `dynamics/workspace.rs`, say) are a cycle. Edges
between a module and its own parent or child (`super::*`, `mod x; use x::Y`) are not counted: a
parent declares its children, and a child reads what the parent re-exports.

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

def sources(crate):
    """Each `.rs` file of `crate` once: its module path ('' for lib.rs and main.rs) and its text
    without comment lines. Both checks below read these, so each file is read once."""
    src=os.path.join(root,crate,'src')
    out={}
    for dp,_,fs in os.walk(src):
        for f in sorted(fs):
            if not f.endswith('.rs'): continue
            p=os.path.join(dp,f); rel=os.path.relpath(p,src)[:-3].replace(os.sep,'::')
            rel=rel.replace('::mod','')
            if rel in ('lib','main'): rel=''
            with open(p) as fh:
                txt='\n'.join(l for l in fh.read().splitlines() if not l.strip().startswith('//'))
            # lib.rs and main.rs are both the crate's root.
            out[rel]=out[rel]+'\n'+txt if rel in out else txt
    return out

SOURCES={crate:sources(crate) for crate in sorted(os.listdir(root))}

for crate,files in SOURCES.items():
    mods={}
    for rel,txt in files.items():
        if rel=='': continue
        top=rel.split('::')[0]
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

def file_cycles(crate):
    """The cycles among the files of `crate`, each as the list of its files' module paths."""
    files=SOURCES[crate]
    def resolve(base,segs):
        """The deepest module file named by `base` then `segs`."""
        best=base
        path=base
        for s in segs:
            path=(path+'::'+s) if path else s
            if path in files: best=path
            else: break
        return best
    edges={m:set() for m in files}
    for m,txt in files.items():
        txt=re.sub(r'#\[cfg\(test\)\]\s*mod tests\s*\{.*','',txt,flags=re.S)
        parent=m.rsplit('::',1)[0] if '::' in m else ''
        for kw,base in (('crate',''),('super',parent),('self',m)):
            for mm in re.finditer(kw+r'::((?:[a-z_][a-z0-9_]*::)*)(\{[^}]*\}|[A-Za-z_][A-Za-z0-9_]*)',txt):
                head=[x for x in mm.group(1).split('::') if x]
                tails=[mm.group(2)]
                if tails[0].startswith('{'):
                    tails=[t.strip() for t in tails[0][1:-1].split(',') if t.strip()]
                for t in tails:
                    segs=head+[x for x in t.split('::') if x and x!='*' and x!='self']
                    d=resolve(base,segs)
                    if d!=m: edges[m].add(d)
    related=lambda a,b: a=='' or b=='' or a.startswith(b+'::') or b.startswith(a+'::')
    for m in edges: edges[m]={d for d in edges[m] if not related(m,d)}
    # Tarjan's strongly connected components.
    index,low,stack,on,out=({},{},[],set(),[])
    def visit(v):
        index[v]=low[v]=len(index); stack.append(v); on.add(v)
        for w in sorted(edges[v]):
            if w not in index: visit(w); low[v]=min(low[v],low[w])
            elif w in on: low[v]=min(low[v],index[w])
        if low[v]==index[v]:
            comp=[]
            while True:
                w=stack.pop(); on.discard(w); comp.append(w)
                if w==v: break
            if len(comp)>1: out.append(sorted(comp))
    sys.setrecursionlimit(10000)
    for v in sorted(edges):
        if v not in index: visit(v)
    return out

for crate in SOURCES:
    for comp in file_cycles(crate):
        print(crate,'files that import each other:',', '.join(comp)); bad+=1

print('check-layers: ' + ('%d problems' % bad if bad else 'no import cycle between modules or files, every layer uses only those below it'))
sys.exit(1 if bad else 0)
